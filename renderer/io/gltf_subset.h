#pragma once
// The part of a glTF 2.0 file Glint reads, and nothing else, for Assimp to import: the scene's
// nodes with their transforms, each primitive's POSITION, NORMAL, TEXCOORD_0, indices and
// material, the accessors, buffer views and buffers behind them, the materials' factors (base
// colour, metallic, roughness, emission; transmission, ior, volume and emissive strength
// extensions) and their base colour and emissive textures with the textures, images and
// samplers behind them. Skins, animations, morph targets, cameras and lights (which Glint reads
// itself, io/gltf_scene.h) are removed before Assimp sees the file, so its readers for them never
// run: Assimp 5.2.5 dereferenced a null pointer on a skin without inverseBindMatrices (found by
// glint_fuzz_mesh). Geometry-compression extensions stay.
#include <string>

namespace glint {

// The glTF JSON `text` of `path` reduced as above. Throws GlintError naming `path` when it is
// not a JSON object (nlohmann's strict reader: invalid UTF-8 is refused, which Assimp's lenient
// reader would take whole), nests more than 64 levels (Assimp's reader recurses once per
// level) or declares a glTF version other than 2.
std::string gltfSubset(const std::string& path, const std::string& text);

// The same for a GLB file's bytes: its JSON chunk is reduced and the container's lengths
// rewritten; the binary chunk is kept as it is. Throws as above, and when the bytes are not a
// GLB 2 container.
std::string glbSubset(const std::string& path, const std::string& bytes);

// A GLB file's JSON chunk; throws GlintError naming `path` when the bytes are not a GLB 2
// container.
std::string glbJsonChunk(const std::string& path, const std::string& bytes);

}  // namespace glint
