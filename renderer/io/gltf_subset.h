#pragma once
// The part of a glTF 2.0 file Glint reads, and nothing else, for Assimp to import: the scene's
// nodes with their transforms, each primitive's POSITION, NORMAL, TANGENT, TEXCOORD_0,
// TEXCOORD_1, indices and material, the accessors, buffer views and buffers behind them, the
// materials' factors (base colour, metallic, roughness, emission; transmission, ior, volume and
// emissive strength extensions) and their base colour, metallic-roughness, occlusion, emissive
// and normal textures with the textures, images and samplers behind them. What else the file
// holds that would change how it looks is named in one warning (io/gltf_dropped.h). Skins,
// animations, morph targets, cameras and lights (which Glint reads itself, io/gltf_scene.h) are
// removed before Assimp sees the file, so its readers for them never run: Assimp 5.2.5
// dereferenced a null pointer on a skin without inverseBindMatrices (found by glint_fuzz_mesh).
// Geometry-compression extensions stay. The textures' KHR_texture_transform, texCoord and
// samplers are read by Glint (io/gltf_texture_transform.h), not by Assimp (whose reader of the
// transform indexes the offset and scale arrays without checking their sizes).
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "materials/image_texture.h"

namespace glint {

// What Glint reads from one of a glTF file's materials itself: its name as the file gives it
// (empty when it has none); how each texture it reads reads the surface (materials/
// image_texture.h): its KHR_texture_transform in Glint's (u, v) (the identity where there is
// none), its texCoord set (0 or 1) and its sampler's wrapS and wrapT; its occlusion texture's
// strength (clamped to [0, 1]), its normal texture's scale, and its
// KHR_materials_emissive_strength (a finite number, at least 0; Assimp 5.2.5's reader does not
// read the extension).
struct GltfMaterialInfo {
  std::string name;
  UvTransform baseColorUv, emissiveUv, metallicRoughnessUv, occlusionUv, normalUv;
  float occlusionStrength = 1;
  float emissiveStrength = 1;
  float normalScale = 1;  // normalTexture.scale
};

// The name a glTF file's material `index` reaches Assimp with, and back (nullopt for a name that
// is not one of these). Assimp 5.2.5 numbers the materials it imports in the order its meshes
// first use them, leaving out those none uses, so its index does not say which of the file's
// materials it holds; this name does.
std::string gltfMaterialTag(size_t index);
std::optional<size_t> gltfMaterialIndex(const std::string& name);

// The glTF JSON `text` of `path`, parsed. Throws UsageError naming `path` when it is not a
// JSON object (nlohmann's strict reader: invalid UTF-8 is refused, which Assimp's lenient
// reader would take whole), nests more than 64 levels (Assimp's reader recurses once per
// level), declares a glTF version other than 2 or places nodes too many times
// (checkGltfExpansion). It warns of nothing.
nlohmann::json parseGltfDocument(const std::string& path, const std::string& text);

// The glTF JSON `text` of `path` reduced as above, after parseGltfDocument's checks; what it
// drops or cannot use is warned about. Given `materials`, it receives one entry per
// element of the file's `materials` (a malformed texture transform is warned about there and
// ignored), and each material's name in the subset is its gltfMaterialTag.
std::string gltfSubset(const std::string& path, const std::string& text,
                       std::vector<GltfMaterialInfo>* materials = nullptr);

// The same for a GLB file's bytes: its JSON chunk is reduced and the container's lengths
// rewritten; the binary chunk is kept as it is. Throws as above, and when the bytes are not a
// GLB 2 container.
std::string glbSubset(const std::string& path, const std::string& bytes,
                      std::vector<GltfMaterialInfo>* materials = nullptr);

// A glTF buffer's or image's `uri` as the file it names in `dir`: glTF URIs are RFC 3986
// references, so "Cesium%20Logo.png" names "Cesium Logo.png" (Assimp 5.2.5 looked for the
// literal name). Decoded where the decoded name is a file or the literal one is not (some
// writers put a name in as it is); a data URI, or one without a valid %XX, as it is.
std::string gltfUriPath(const std::string& uri, const std::string& dir);

// A GLB file's JSON chunk; throws GlintError naming `path` when the bytes are not a GLB 2
// container.
std::string glbJsonChunk(const std::string& path, const std::string& bytes);

}  // namespace glint
