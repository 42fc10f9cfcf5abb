#include "io/gltf_dropped.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <string_view>

#include "core/error.h"

namespace glint {

namespace {

using nlohmann::json;

// The extensions Glint renders (materials, io/mesh_materials.h; texture transforms; a file's
// lights where it is the scene, io/gltf_scene.h) or that only encode geometry Assimp decodes.
// (KHR_mesh_quantization's integer positions Assimp does not: io/gltf_layout.h refuses them.)
constexpr std::string_view kRendered[] = {
    "KHR_materials_transmission",      "KHR_materials_ior",     "KHR_materials_volume",
    "KHR_materials_emissive_strength", "KHR_texture_transform", "KHR_lights_punctual",
    "KHR_draco_mesh_compression"};

bool rendered(std::string_view extension) {
  return std::find(std::begin(kRendered), std::end(kRendered), extension) != std::end(kRendered);
}

// What is dropped, in the order first met, with how many materials or primitives have it and
// the textures an extension brings.
struct Tally {
  std::vector<std::string> order;
  std::map<std::string, size_t> count;
  std::map<std::string, std::vector<std::string>> textures;

  void add(const std::string& what, size_t n = 1) {
    if (!count.count(what)) order.push_back(what);
    count[what] += n;
  }
  void addTexture(const std::string& what, const std::string& texture) {
    auto& list = textures[what];
    if (std::find(list.begin(), list.end(), texture) == list.end()) list.push_back(texture);
  }
};

std::string plural(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::vector<std::string> gltfDroppedFeatures(const json& doc) {
  if (!doc.is_object()) return {};
  Tally materials, declared;
  if (const auto used = doc.find("extensionsUsed"); used != doc.end() && used->is_array())
    for (const json& name : *used)
      if (name.is_string() && !rendered(name.get<std::string>()))
        declared.add(excerpt(name.get<std::string>()));
  if (const auto list = doc.find("materials"); list != doc.end() && list->is_array())
    for (const json& m : *list) {
      if (!m.is_object()) continue;
      const auto extensions = m.find("extensions");
      if (extensions == m.end() || !extensions->is_object()) continue;
      for (const auto& [name, extension] : extensions->items()) {
        const std::string ext = excerpt(name);
        const bool own = rendered(name);
        if (!own) materials.add(ext);
        if (!extension.is_object()) continue;
        // An extension's textures are its keys that end in "Texture" (clearcoatTexture,
        // transmissionTexture, thicknessTexture, ...).
        for (const auto& [key, value] : extension.items()) {
          if (key.size() < 7 || key.compare(key.size() - 7, 7, "Texture") != 0) continue;
          if (own)
            materials.add(ext + "'s " + excerpt(key));
          else
            materials.addTexture(ext, excerpt(key));
        }
      }
    }
  size_t skins = 0, animations = 0, morphed = 0, pointsAndLines = 0;
  for (const char* key : {"skins", "animations"})
    if (const auto it = doc.find(key); it != doc.end() && it->is_array())
      (key[0] == 's' ? skins : animations) = it->size();
  if (const auto meshes = doc.find("meshes"); meshes != doc.end() && meshes->is_array())
    for (const json& mesh : *meshes) {
      if (!mesh.is_object()) continue;
      const auto primitives = mesh.find("primitives");
      if (primitives == mesh.end() || !primitives->is_array()) continue;
      for (const json& p : *primitives) {
        if (!p.is_object()) continue;
        if (const auto t = p.find("targets"); t != p.end() && t->is_array() && !t->empty())
          ++morphed;
        if (const auto mode = p.find("mode");
            mode != p.end() && mode->is_number_integer() && *mode >= 0 && *mode <= 3)
          ++pointsAndLines;
      }
    }

  std::vector<std::string> out;
  // Material extensions with where they are and their textures; declared ones that no material
  // carries (KHR_materials_variants, EXT_texture_webp, ...) by name.
  for (const std::string& what : materials.order) {
    std::string line = what + " (" + plural(materials.count[what], "material", "materials");
    if (const auto t = materials.textures.find(what); t != materials.textures.end()) {
      line += ", with its ";
      for (size_t i = 0; i < t->second.size(); ++i) line += (i ? ", " : "") + t->second[i];
    }
    out.push_back(line + ")");
  }
  for (const std::string& what : declared.order)
    if (!materials.count.count(what)) out.push_back(what);
  if (skins) out.push_back(plural(skins, "skin", "skins"));
  if (morphed)
    out.push_back("morph targets (on " + plural(morphed, "primitive", "primitives") + ")");
  if (animations) out.push_back(plural(animations, "animation", "animations"));
  if (pointsAndLines)
    out.push_back(plural(pointsAndLines, "point or line primitive", "point and line primitives"));
  return out;
}

}  // namespace glint
