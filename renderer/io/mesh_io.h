#pragma once
// Triangle meshes from files through Assimp: OBJ, PLY, glTF 2.0 and the other formats Assimp
// reads. All meshes of the file are merged, with their node transforms applied.
#include <string>

#include "geometry/triangle_mesh.h"

namespace glint {

// Throws GlintError naming the path tried and Assimp's reason.
TriangleMesh loadMeshFile(const std::string& path);

}  // namespace glint
