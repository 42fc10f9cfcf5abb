#pragma once
// Tangent frames for normal maps on triangle meshes that do not give their own: MikkTSpace
// (Mikkelsen 2008), which glTF 2.0 requires ("When tangents are not specified, client
// implementations SHOULD calculate tangents using default MikkTSpace algorithms"), so that a
// normal map baked against it is read back in the frame it was baked in.
#include <vector>

#include "geometry/triangle_mesh.h"

namespace glint {

// Per triangle corner (TriangleMesh::tangents) from the mesh's positions (at key 0 for a
// deforming mesh), its vertex normals (the triangles' own where it has none) and its texture
// coordinates (each triangle's (0,0), (1,0), (0,1) where it has none, as Scene reads it). A
// corner of a degenerate triangle takes its neighbours' frame, or any tangent across its normal.
// Throws OutOfMemoryError (core/error.h) when MikkTSpace's working memory would not fit.
std::vector<TriangleMesh::Tangent> generateTangents(const TriangleMesh& mesh);

}  // namespace glint
