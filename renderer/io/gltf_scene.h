#pragma once
// What a glTF 2.0 file says about its scene beyond the meshes (which Assimp places,
// io/mesh_io.h): its cameras and its KHR_lights_punctual lights, each placed by the node tree
// of the file's default scene (every node's transform composed with its parents').
#include <string>

#include "io/file_scene_info.h"

namespace glint {

// Reads the cameras and lights of the .gltf or .glb file `path`. Throws UsageError naming the
// file and the node, camera or light that is wrong (a node that is its own ancestor, an index
// out of range, a non-finite or singular transform, a camera without its parameters).
FileSceneInfo readGltfSceneInfo(const std::string& path);

}  // namespace glint
