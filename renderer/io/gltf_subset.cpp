#include "io/gltf_subset.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/input_files.h"
#include "core/json_memory.h"
#include "core/log.h"
#include "io/gltf_dropped.h"
#include "io/gltf_expansion.h"
#include "io/gltf_layout.h"
#include "io/gltf_texture_transform.h"

namespace glint {

namespace {

using nlohmann::json;

constexpr int kMaxDepth = 64;

// The deepest nesting of arrays and objects, counted without parsing (strings skipped).
int nestingDepth(const std::string& text) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

// Keeps only `keys` of the object `j` (anything else is left as it is).
void keepOnly(json& j, std::initializer_list<const char*> keys) {
  if (!j.is_object()) return;
  json kept = json::object();
  for (const char* k : keys)
    if (const auto it = j.find(k); it != j.end()) kept[k] = std::move(*it);
  j = std::move(kept);
}

template <typename F>
void forEachIn(json& j, const char* key, F&& f) {
  if (const auto it = j.find(key); it != j.end() && it->is_array())
    for (json& element : *it) f(element);
}

// Whether `key` of `object` (when there) is an index below `count`.
bool indexBelow(const json& object, const char* key, size_t count) {
  const auto it = object.find(key);
  return it == object.end() || (it->is_number_unsigned() && it->get<size_t>() < count);
}

size_t countOf(const json& doc, const char* key) {
  const auto it = doc.find(key);
  return it != doc.end() && it->is_array() ? it->size() : 0;
}

// glTF 2.0 requires a buffer view's byteStride to hold a whole element of each accessor reading
// it (the validator's ACCESSOR_SMALL_BYTESTRIDE). Assimp 5.2.5 reads overlapping elements
// instead, and the mesh rendered as other geometry, without a word.
void checkStrides(const std::string& path, const json& doc) {
  const size_t views = countOf(doc, "bufferViews");
  for (size_t i = 0; i < countOf(doc, "accessors"); ++i) {
    const json& accessor = doc["accessors"][i];
    if (!accessor.is_object() || !indexBelow(accessor, "bufferView", views)) continue;
    const auto viewIndex = accessor.find("bufferView");
    if (viewIndex == accessor.end()) continue;
    const json& view = doc["bufferViews"][viewIndex->get<size_t>()];
    const auto stride = view.is_object() ? view.find("byteStride") : view.end();
    if (stride == view.end() || !stride->is_number_unsigned()) continue;
    const uint64_t element = gltfElementBytes(accessor);
    if (stride->get<uint64_t>() < element)
      throw UsageError("mesh " + path + ": accessors[" + std::to_string(i) +
                       "] reads bufferViews[" + std::to_string(viewIndex->get<size_t>()) +
                       "], whose byteStride " + std::to_string(stride->get<uint64_t>()) +
                       " is less than its " + std::to_string(element) +
                       "-byte elements, which would overlap (glTF 2.0 requires the stride to "
                       "hold an element)");
  }
}

// glTF 2.0 allows texture coordinates as normalized unsigned bytes or shorts too (quantized
// files); Assimp 5.2.5 reads only floats and took the others' bytes for floats: one colour of
// the texture over the whole mesh, or a refusal naming NaN coordinates that the file lacks.
// Such a set is removed from its primitive, with a warning: the mesh renders, its textures
// read at (0, 0).
void dropTextureCoordinatesNotFloat(const std::string& path, json& doc) {
  const size_t accessors = countOf(doc, "accessors");
  std::string dropped;
  for (size_t m = 0; m < countOf(doc, "meshes"); ++m) {
    json& mesh = doc["meshes"][m];
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (primitives == mesh.end() || !primitives->is_array()) continue;
    for (size_t p = 0; p < primitives->size(); ++p) {
      json& primitive = (*primitives)[p];
      const auto attributes =
          primitive.is_object() ? primitive.find("attributes") : primitive.end();
      if (attributes == primitive.end() || !attributes->is_object()) continue;
      for (const char* set : {"TEXCOORD_0", "TEXCOORD_1"}) {
        if (!attributes->contains(set) || !indexBelow(*attributes, set, accessors)) continue;
        const json& accessor = doc["accessors"][(*attributes)[set].get<size_t>()];
        const auto type = accessor.is_object() ? accessor.find("componentType") : accessor.end();
        if (type == accessor.end() || !type->is_number_unsigned() || type->get<uint64_t>() == 5126)
          continue;
        if (dropped.empty())
          dropped = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]'s " +
                    set + " (" +
                    (type->get<uint64_t>() == 5121   ? "unsigned bytes"
                     : type->get<uint64_t>() == 5123 ? "unsigned shorts"
                                                     : "integers") +
                    ")";
        attributes->erase(set);
      }
    }
  }
  if (!dropped.empty())
    log::warning("mesh " + path + ": texture coordinates stored as integers (quantized), first " +
                 dropped +
                 ", are left out: Glint reads them stored as floats only, and its "
                 "textures are read at (0, 0) there");
}

// The reduced file's textures, images and samplers, and the materials' references to them:
// every reference an index in range, every image a URI or an embedded PNG or JPEG.
bool texturesAreWellFormed(const json& doc) {
  const size_t textures = countOf(doc, "textures"), images = countOf(doc, "images"),
               samplers = countOf(doc, "samplers");
  for (const char* key : {"textures", "images", "samplers"})
    if (doc.contains(key) && !doc[key].is_array()) return false;
  for (size_t i = 0; i < textures; ++i) {
    const json& t = doc["textures"][i];
    if (!t.is_object() || !indexBelow(t, "source", images) || !indexBelow(t, "sampler", samplers))
      return false;
  }
  for (size_t i = 0; i < images; ++i) {
    const json& image = doc["images"][i];
    if (!image.is_object()) return false;
    if (image.contains("uri")) {
      if (!image["uri"].is_string()) return false;
      continue;
    }
    const auto mime = image.find("mimeType");
    if (!image.contains("bufferView") ||
        !indexBelow(image, "bufferView", countOf(doc, "bufferViews")) || mime == image.end() ||
        !mime->is_string() || (*mime != "image/png" && *mime != "image/jpeg"))
      return false;
  }
  for (size_t i = 0; i < countOf(doc, "materials"); ++i) {
    const json& m = doc["materials"][i];
    if (!m.is_object()) continue;
    const auto textureInfoOk = [&](const json& owner, const char* key) {
      const auto info = owner.find(key);
      return info == owner.end() ||
             (info->is_object() && info->contains("index") && indexBelow(*info, "index", textures));
    };
    if (!textureInfoOk(m, "emissiveTexture") || !textureInfoOk(m, "occlusionTexture") ||
        !textureInfoOk(m, "normalTexture"))
      return false;
    if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end() && pbr->is_object())
      if (!textureInfoOk(*pbr, "baseColorTexture") ||
          !textureInfoOk(*pbr, "metallicRoughnessTexture"))
        return false;
  }
  return true;
}

// The textureInfo `owner[key]`; null where there is none.
json textureInfoOf(const json& owner, const char* key) {
  if (!owner.is_object()) return nullptr;
  const auto info = owner.find(key);
  return info == owner.end() || !info->is_object() ? json() : *info;
}

// The textures Glint reads of a material, in GltfMaterialInfo's order.
enum Slot { BaseColor, Emissive, MetallicRoughness, Occlusion, Normal, kSlots };

// How the well-formed textureInfo `info` (JSON null: none) of the reduced `doc` reads the
// surface: its KHR_texture_transform, its texCoord (0 or 1; another is warned about and read as
// 0) and its texture's sampler's wrap modes (a value glTF does not define is warned about and
// read as REPEAT). Messages name `where`.
UvTransform textureReading(const json& doc, const json& info, const std::string& where) {
  if (info.is_null()) return {};
  int set = 0;
  if (const auto texCoord = info.find("texCoord"); texCoord != info.end()) {
    if (texCoord->is_number_unsigned() && texCoord->get<uint64_t>() <= 1)
      set = texCoord->get<int>();
    else
      log::warning(where + "'s texCoord " + excerpt(texCoord->dump()) +
                   " is not read (Glint reads TEXCOORD_0 and TEXCOORD_1): TEXCOORD_0 is");
  }
  json transform;
  if (const auto extensions = info.find("extensions");
      extensions != info.end() && extensions->is_object())
    if (const auto t = extensions->find("KHR_texture_transform"); t != extensions->end())
      transform = *t;
  UvTransform reading = gltfTextureTransform(transform, where, set);
  const json& texture = doc["textures"][info["index"].get<size_t>()];
  const auto sampler = texture.find("sampler");
  if (sampler == texture.end()) return reading;
  const json& wraps = doc["samplers"][sampler->get<size_t>()];
  const auto wrapOf = [&](const char* key) {
    const auto w = wraps.is_object() ? wraps.find(key) : wraps.end();
    if (w == wraps.end()) return TextureWrap::Repeat;
    // OpenGL's enums, as glTF's sampler gives them.
    if (*w == 33071) return TextureWrap::ClampToEdge;
    if (*w == 33648) return TextureWrap::MirroredRepeat;
    if (*w != 10497)
      log::warning(where + ": its sampler's " + key + " " + excerpt(w->dump()) +
                   " is not a glTF wrap mode (33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT, 10497 "
                   "REPEAT): it repeats");
    return TextureWrap::Repeat;
  };
  reading.wrapS = wrapOf("wrapS");
  reading.wrapT = wrapOf("wrapT");
  return reading;
}

// normalTexture.scale: 1 where it is absent or not a finite number.
float normalTextureScale(const json& material) {
  const auto info = material.find("normalTexture");
  if (info == material.end() || !info->is_object()) return 1;
  const auto scale = info->find("scale");
  if (scale == info->end() || !scale->is_number()) return 1;
  const double v = scale->get<double>();
  return std::isfinite(v) && std::fabs(v) <= 1e6 ? static_cast<float>(v) : 1.0f;
}

constexpr std::string_view kMaterialTag = "glint:gltf-material:";

}  // namespace

std::string gltfMaterialTag(size_t index) {
  return std::string(kMaterialTag) + std::to_string(index);
}

std::optional<size_t> gltfMaterialIndex(const std::string& name) {
  if (name.compare(0, kMaterialTag.size(), kMaterialTag) != 0) return std::nullopt;
  const char *first = name.data() + kMaterialTag.size(), *last = name.data() + name.size();
  size_t index = 0;
  const auto [end, error] = std::from_chars(first, last, index);
  if (error != std::errc() || end != last || first == last) return std::nullopt;
  return index;
}

std::string gltfUriPath(const std::string& uri, const std::string& dir) {
  if (uri.rfind("data:", 0) == 0 || uri.find('%') == std::string::npos) return uri;
  std::string decoded;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      decoded += uri[i];
      continue;
    }
    unsigned byte = 0;
    const char* digits = uri.data() + i + 1;
    if (i + 2 >= uri.size() || std::from_chars(digits, digits + 2, byte, 16).ptr != digits + 2)
      return uri;  // not an escape: a name with a '%' in it
    decoded += char(byte);
    i += 2;
  }
  // Escapes of bytes that are not UTF-8 ("caf%E9.png", Latin-1) could not be written back into
  // the JSON: kept as written, so that a missing file stays a missing file.
  if (!isUtf8(decoded)) return uri;
  std::error_code ec;
  const std::filesystem::path base(dir);
  return std::filesystem::exists(base / decoded, ec) || !std::filesystem::exists(base / uri, ec)
             ? decoded
             : uri;
}

json parseGltfDocument(const std::string& path, const std::string& text) {
  if (nestingDepth(text) > kMaxDepth)
    throw UsageError("mesh " + path + ": its JSON nests more than " + std::to_string(kMaxDepth) +
                     " levels deep (a glTF file needs about 6)");
  checkJsonTreeFits(text, 0, 0, "glTF " + path);
  // Only what Glint has parsed reaches Assimp: a file nlohmann's strict reader refuses (invalid
  // UTF-8, say) is refused here, since Assimp's lenient one would read all of it, skins too.
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw UsageError("mesh " + path + ": not glTF JSON: " + excerpt(e.what()));
  }
  if (!doc.is_object()) throw UsageError("mesh " + path + ": not glTF: not a JSON object");
  // glTF 1.0 files give their version as "1.0" or as the number 1 (Cesium's exporters), and
  // keep nodes, meshes and the rest in objects keyed by name where glTF 2.0 has arrays: named
  // here rather than reported as "nodes is not an array".
  const std::string glTF1 = "mesh " + path + ": glTF 1.0 is not supported; Glint reads glTF 2.0";
  if (const auto asset = doc.find("asset"); asset != doc.end() && asset->is_object()) {
    const auto version = asset->find("version");
    if (version != asset->end() && version->is_number() && version->get<double>() < 2)
      throw UsageError(glTF1 + " (asset.version is " + version->dump() + ")");
    if (version != asset->end() && version->is_string() &&
        version->get<std::string>().rfind("1", 0) == 0)
      throw UsageError(glTF1 + " (asset.version is " +
                       inQuotes(excerpt(version->get<std::string>())) + ")");
    if (version != asset->end() && version->is_string() &&
        version->get<std::string>().rfind("2", 0) != 0)
      throw UsageError("mesh " + path + " is glTF " + excerpt(version->get<std::string>()) +
                       "; Glint reads glTF 2.0");
  }
  for (const char* key : {"nodes", "meshes", "accessors", "bufferViews", "buffers"})
    if (const auto it = doc.find(key); it != doc.end() && it->is_object())
      throw UsageError("mesh " + path + ": its \"" + key +
                       "\" is an object keyed by name, as in glTF 1.0, which is not supported; "
                       "Glint reads glTF 2.0");
  // Before Assimp or Glint's own reader (cameras and lights) places a node once per path to it.
  checkGltfExpansion(path, doc);
  return doc;
}

std::string gltfSubset(const std::string& path, const std::string& text,
                       std::vector<GltfMaterialInfo>* materials) {
  json doc = parseGltfDocument(path, text);
  // Named before anything is removed (io/gltf_dropped.h), warned about once the file is taken.
  const std::vector<std::string> dropped = gltfDroppedFeatures(doc);
  // URIs decoded for Assimp, which opens them as C strings: "b.bin\u0000x" (or "b.bin%00x")
  // would open b.bin behind a name that says otherwise (core/input_files.h).
  const std::string dir = std::filesystem::path(path).parent_path().string();
  for (const char* key : {"buffers", "images"})
    for (size_t i = 0; i < countOf(doc, key); ++i)
      if (json& item = doc[key][i];
          item.is_object() && item.contains("uri") && item["uri"].is_string()) {
        item["uri"] = gltfUriPath(item["uri"].get<std::string>(), dir);
        checkPathCharacters(item["uri"].get<std::string>(),
                            "mesh " + path + ": " + key + "[" + std::to_string(i) + "].uri");
      }
  checkStrides(path, doc);
  dropTextureCoordinatesNotFloat(path, doc);
  keepOnly(doc,
           {"asset", "scene", "scenes", "nodes", "meshes", "materials", "accessors", "bufferViews",
            "buffers", "textures", "images", "samplers", "extensionsUsed", "extensionsRequired"});
  // The materials' names, each then replaced by its tag, and the textureInfos Glint reads
  // (read once the textures are known to be well formed, below).
  std::vector<std::array<json, kSlots>> textureInfos;
  if (materials) {
    materials->assign(countOf(doc, "materials"), {});
    textureInfos.resize(materials->size());
    for (size_t i = 0; i < materials->size(); ++i) {
      json& material = doc["materials"][i];
      if (!material.is_object()) continue;
      if (const auto name = material.find("name"); name != material.end() && name->is_string())
        (*materials)[i].name = name->get<std::string>();
      material["name"] = gltfMaterialTag(i);
      const auto pbr = material.find("pbrMetallicRoughness");
      const json& pbrOrNull = pbr != material.end() ? *pbr : json();
      textureInfos[i][BaseColor] = textureInfoOf(pbrOrNull, "baseColorTexture");
      textureInfos[i][Emissive] = textureInfoOf(material, "emissiveTexture");
      textureInfos[i][MetallicRoughness] = textureInfoOf(pbrOrNull, "metallicRoughnessTexture");
      textureInfos[i][Occlusion] = textureInfoOf(material, "occlusionTexture");
      textureInfos[i][Normal] = textureInfoOf(material, "normalTexture");
      (*materials)[i].normalScale = normalTextureScale(material);
      if (const json& occlusion = textureInfos[i][Occlusion]; occlusion.is_object())
        if (const auto strength = occlusion.find("strength"); strength != occlusion.end()) {
          const double v = strength->is_number() ? strength->get<double>() : -1;
          const bool inRange = v >= 0 && v <= 1;  // false for NaN
          (*materials)[i].occlusionStrength = inRange ? float(v) : v > 1 ? 1.0f : 0.0f;
          if (!inRange)
            log::warning("mesh " + path + ": materials[" + std::to_string(i) +
                         "]: occlusionTexture's strength " + excerpt(strength->dump()) +
                         " is not a number from 0 to 1: " + (v > 1 ? "1" : "0") + " is used");
        }
      if (const auto ext = material.find("extensions"); ext != material.end() && ext->is_object())
        if (const auto e = ext->find("KHR_materials_emissive_strength");
            e != ext->end() && e->is_object())
          if (const auto strength = e->find("emissiveStrength"); strength != e->end()) {
            const double v = strength->is_number() ? strength->get<double>() : -1;
            if (v >= 0 && v <= 3.4e38)
              (*materials)[i].emissiveStrength = float(v);
            else  // the extension's default, said aloud
              log::warning("mesh " + path + ": materials[" + std::to_string(i) +
                           "]: KHR_materials_emissive_strength's emissiveStrength " +
                           excerpt(strength->dump()) +
                           " is not a number from 0 to 3.4e38: 1 is used");
          }
    }
  }
  // Materials as their factors and textures (io/mesh_materials.h).
  const auto keepTextureInfo = [](json& object, const char* key) {
    if (const auto info = object.find(key); info != object.end()) keepOnly(*info, {"index"});
  };
  forEachIn(doc, "materials", [&](json& material) {
    keepOnly(material,
             {"name", "pbrMetallicRoughness", "emissiveFactor", "emissiveTexture",
              "occlusionTexture", "alphaMode", "alphaCutoff", "extensions", "normalTexture"});
    if (!material.is_object()) return;
    keepTextureInfo(material, "emissiveTexture");
    keepTextureInfo(material, "occlusionTexture");
    keepTextureInfo(material, "normalTexture");
    if (const auto pbr = material.find("pbrMetallicRoughness"); pbr != material.end()) {
      keepOnly(*pbr, {"baseColorFactor", "baseColorTexture", "metallicFactor", "roughnessFactor",
                      "metallicRoughnessTexture"});
      if (pbr->is_object()) {
        keepTextureInfo(*pbr, "baseColorTexture");
        keepTextureInfo(*pbr, "metallicRoughnessTexture");
      }
    }
    if (const auto ext = material.find("extensions"); ext != material.end()) {
      keepOnly(*ext, {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                      "KHR_materials_emissive_strength"});
      if (!ext->is_object()) return;
      const auto keep = [&](const char* name, std::initializer_list<const char*> keys) {
        if (const auto e = ext->find(name); e != ext->end()) keepOnly(*e, keys);
      };
      keep("KHR_materials_transmission", {"transmissionFactor"});
      keep("KHR_materials_ior", {"ior"});
      keep("KHR_materials_volume", {"thicknessFactor", "attenuationDistance", "attenuationColor"});
      keep("KHR_materials_emissive_strength", {"emissiveStrength"});
    }
  });
  forEachIn(doc, "nodes", [](json& node) {
    keepOnly(node, {"name", "children", "matrix", "translation", "rotation", "scale", "mesh"});
  });
  forEachIn(doc, "meshes", [](json& mesh) {
    keepOnly(mesh, {"name", "primitives"});
    if (!mesh.is_object()) return;
    // Only triangles (mode 4, the default, strips 5 and fans 6): Glint skips points and lines,
    // and Assimp's line-loop reader dereferenced null for an index past the vertices (SEGV,
    // found by glint_fuzz_mesh), so those primitives never reach it.
    if (const auto p = mesh.find("primitives"); p != mesh.end() && p->is_array()) {
      json triangles = json::array();
      for (json& primitive : *p) {
        const auto mode = primitive.is_object() ? primitive.find("mode") : primitive.end();
        if (!primitive.is_object() || mode == primitive.end() ||
            (mode->is_number_integer() && *mode >= 4 && *mode <= 6))
          triangles.push_back(std::move(primitive));
      }
      *p = std::move(triangles);
    }
    forEachIn(mesh, "primitives", [](json& primitive) {
      keepOnly(primitive, {"attributes", "indices", "mode", "material", "extensions"});
      if (const auto a = primitive.find("attributes"); a != primitive.end())
        keepOnly(*a, {"POSITION", "NORMAL", "TANGENT", "TEXCOORD_0", "TEXCOORD_1", "COLOR_0"});
    });
  });
  // Once the primitives are those Assimp reads.
  checkGltfBufferLayout(path, doc);
  forEachIn(doc, "textures", [](json& texture) { keepOnly(texture, {"source", "sampler"}); });
  forEachIn(doc, "images", [](json& image) {
    keepOnly(image, {"name", "uri", "mimeType", "bufferView"});
  });
  forEachIn(doc, "samplers", [](json& sampler) { keepOnly(sampler, {"wrapS", "wrapT"}); });
  // A texture whose image only an extension names (KHR_texture_basisu, EXT_texture_webp) has no
  // source: Assimp dropped it without a word.
  size_t sourceless = 0, firstSourceless = 0;
  for (size_t t = countOf(doc, "textures"); t-- > 0;)
    if (const json& texture = doc["textures"][t];
        texture.is_object() && !texture.contains("source")) {
      ++sourceless;
      firstSourceless = t;
    }
  if (sourceless > 0)
    log::warning("mesh " + path + ": " + std::to_string(sourceless) + " texture(s), textures[" +
                 std::to_string(firstSourceless) +
                 "] first, name no source image Glint reads (an extension's image, or none): "
                 "the materials using them render without them");
  const bool texturesKept = texturesAreWellFormed(doc);
  if (!texturesKept) {
    // Assimp 5.2.5 trusts them: an embedded image whose mimeType was not image/... made its
    // reader strcmp a null pointer (SEGV, found by glint_fuzz_mesh). The file keeps its
    // geometry and colour factors.
    log::warning("mesh " + path +
                 ": its textures are malformed (an index out of range, or an embedded image "
                 "that is not image/png or image/jpeg); they are left out");
    doc.erase("textures");
    doc.erase("images");
    doc.erase("samplers");
    forEachIn(doc, "materials", [](json& material) {
      if (!material.is_object()) return;
      material.erase("emissiveTexture");
      material.erase("occlusionTexture");
      material.erase("normalTexture");
      if (const auto pbr = material.find("pbrMetallicRoughness");
          pbr != material.end() && pbr->is_object()) {
        pbr->erase("baseColorTexture");
        pbr->erase("metallicRoughnessTexture");
      }
    });
  }
  for (size_t i = 0; materials && texturesKept && i < materials->size(); ++i) {
    GltfMaterialInfo& m = (*materials)[i];
    const std::string where = "mesh " + path + ": material " + std::to_string(i) +
                              (m.name.empty() ? "" : " " + inQuotes(excerpt(m.name)));
    m.baseColorUv = textureReading(doc, textureInfos[i][BaseColor], where + " baseColorTexture");
    m.emissiveUv = textureReading(doc, textureInfos[i][Emissive], where + " emissiveTexture");
    m.metallicRoughnessUv = textureReading(doc, textureInfos[i][MetallicRoughness],
                                           where + " metallicRoughnessTexture");
    m.occlusionUv = textureReading(doc, textureInfos[i][Occlusion], where + " occlusionTexture");
    m.normalUv = textureReading(doc, textureInfos[i][Normal], where + " normalTexture");
  }
  if (!dropped.empty()) {
    std::string list;
    for (const std::string& feature : dropped) list += (list.empty() ? "" : "; ") + feature;
    log::warning("mesh " + path + ": Glint does not render " + list +
                 " (the rest of the file is rendered without them)");
  }
  try {
    return doc.dump();
  } catch (const json::exception& e) {
    throw UsageError("mesh " + path + ": not glTF JSON: " + excerpt(e.what()));
  }
}

std::string glbJsonChunk(const std::string& path, const std::string& bytes) {
  // 12-byte header (magic, version 2, total length), then chunks of (length, type, data); the
  // first is JSON.
  const auto u32 = [&](size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  if (bytes.size() >= 8 && bytes.compare(0, 4, "glTF") == 0 && u32(4) == 1)
    throw UsageError("mesh " + path +
                     ": binary glTF 1.0 is not supported; Glint reads glTF 2.0 (GLB version 2)");
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || u32(4) != 2 ||
      u32(16) != 0x4E4F534Au)
    throw UsageError("mesh " + path +
                     ": not a GLB 2 file (magic \"glTF\", version 2, a JSON chunk first)");
  if (20 + uint64_t{u32(12)} > bytes.size())
    throw UsageError("mesh " + path + ": its JSON chunk claims " + std::to_string(u32(12)) +
                     " bytes, but the file holds " + std::to_string(bytes.size() - 20) +
                     " after the chunk's header (a cut or damaged GLB file)");
  return bytes.substr(20, u32(12));
}

std::string glbSubset(const std::string& path, const std::string& bytes,
                      std::vector<GltfMaterialInfo>* materials) {
  const std::string json = glbJsonChunk(path, bytes);
  const uint64_t jsonLength = json.size();
  std::string text = gltfSubset(path, json, materials);
  text.append((4 - text.size() % 4) % 4, ' ');  // chunks are 4-byte aligned, padded with spaces
  const std::string rest = bytes.substr(20 + jsonLength);
  std::string out = bytes.substr(0, 12);
  const auto put = [&](size_t at, uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
  const uint32_t chunk[2] = {uint32_t(text.size()), 0x4E4F534Au};
  out.append(reinterpret_cast<const char*>(chunk), 8);
  out += text;
  out += rest;
  put(8, uint32_t(out.size()));
  return out;
}

}  // namespace glint
