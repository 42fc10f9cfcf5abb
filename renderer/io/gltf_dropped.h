#pragma once
// What a glTF 2.0 file holds that changes how it looks and Glint does not render: extensions
// (the file's extensionsUsed and its materials' own), the textures of the material extensions
// Glint reads that it does not, material textures it does not read, skins, morph targets,
// animations, and point and line primitives. The file's loader names them in one warning
// (io/gltf_subset.h), so that a look developer knows what is missing, once per file.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace glint {

// One entry per dropped feature, each naming it and where it is (the materials or primitives
// that have it); empty when Glint renders everything `doc` (a glTF file's JSON) holds.
std::vector<std::string> gltfDroppedFeatures(const nlohmann::json& doc);

}  // namespace glint
