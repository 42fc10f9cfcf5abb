#pragma once
// Triangle meshes from files through Assimp: OBJ, PLY and glTF 2.0 (.gltf, .glb) only, each
// checked before Assimp reads it (io/mesh_limits.h). All meshes of the file are merged, with
// their node transforms applied; the file's vertex normals are kept when every mesh has them.
#include <string>

#include "geometry/triangle_mesh.h"

namespace glint {

// Throws GlintError naming the path tried and the reason (Glint's or Assimp's).
TriangleMesh loadMeshFile(const std::string& path);

}  // namespace glint
