#include "io/gltf_indices.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <variant>

#include "core/error.h"
#include "core/input_files.h"
#include "io/gltf_layout.h"
#include "io/gltf_subset.h"
#include "io/mesh_limits.h"

namespace glint {

namespace {

using nlohmann::json;

uint32_t u32At(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

std::optional<uint64_t> unsignedOf(const json& object, const char* key, uint64_t otherwise) {
  const auto it = object.find(key);
  if (it == object.end()) return otherwise;
  if (!it->is_number_unsigned()) return std::nullopt;
  return it->get<uint64_t>();
}

// The bytes of base64 `text`, or the offset of its first character that is not base64 (padding
// included: only '=' may follow '=').
std::variant<std::string, size_t> base64Decode(const std::string& text) {
  static const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t bits = 0;
  int count = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '=') {
      const size_t other = text.find_first_not_of('=', i);
      if (other != std::string::npos) return other;
      break;
    }
    const size_t v = alphabet.find(c);
    if (v == std::string::npos) return i;
    bits = (bits << 6) | uint32_t(v);
    if ((count += 6) >= 8) {
      count -= 8;
      out += char((bits >> count) & 0xff);
    }
  }
  return out;
}

// The bytes of the file's buffers, read once each as they are asked for; null when a buffer
// cannot be located (Assimp then says why, or finds the file its own way).
class Buffers {
 public:
  Buffers(const std::string& path, const json& doc, const std::string& glbBinary)
      : path_(path),
        dir_(std::filesystem::path(path).parent_path()),
        doc_(doc),
        glbBinary_(glbBinary) {}

  const std::string* get(uint64_t index) {
    if (const auto it = read_.find(index); it != read_.end())
      return it->second ? &*it->second : nullptr;
    std::optional<std::string>& slot = read_[index];
    const auto buffers = doc_.find("buffers");
    if (buffers == doc_.end() || !buffers->is_array() || index >= buffers->size()) return nullptr;
    const json& buffer = (*buffers)[index];
    if (!buffer.is_object()) return nullptr;
    const auto uri = buffer.find("uri");
    if (uri == buffer.end()) {
      if (index == 0 && !glbBinary_.empty()) slot = glbBinary_;
      return slot ? &*slot : nullptr;
    }
    if (!uri->is_string()) return nullptr;
    const std::string name = uri->get<std::string>();
    if (name.rfind("data:", 0) == 0) {
      const size_t comma = name.find(',');
      if (comma == std::string::npos || name.rfind(";base64", comma) == std::string::npos)
        return nullptr;
      // Assimp decoded what it could of bad base64 and read zeros after it, without a word.
      auto bytes = base64Decode(name.substr(comma + 1));
      if (const size_t* bad = std::get_if<size_t>(&bytes))
        throw GlintError("mesh " + path_ + ": buffers[" + std::to_string(index) +
                         "].uri is a data URI whose base64 has " +
                         inQuotes(std::string(1, name[comma + 1 + *bad])) + " at character " +
                         std::to_string(comma + 1 + *bad) +
                         "; base64 is A-Z, a-z, 0-9, + and /, "
                         "then = padding");
      slot = std::move(std::get<std::string>(bytes));
      return &*slot;
    }
    std::filesystem::path file(gltfUriPath(name, dir_.string()));
    if (file.is_relative()) file = dir_ / file;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return nullptr;
    checkInputFile(file.string(), kMaxMeshFileBytes, "glTF buffer");
    std::ifstream in(file, std::ios::binary);
    slot = std::string(std::istreambuf_iterator<char>(in), {});
    return &*slot;
  }

 private:
  std::string path_;
  std::filesystem::path dir_;
  const json& doc_;
  const std::string& glbBinary_;
  std::map<uint64_t, std::optional<std::string>> read_;
};

// The bytes of `count` values of `size` bytes at `offset` in buffer view `viewIndex`; null where
// they are not all there (Assimp reports that itself).
const char* viewBytes(const json& doc, Buffers& buffers, const json& viewIndex, uint64_t offset,
                      uint64_t count, uint64_t size) {
  const json* view = gltfElementAt(doc, "bufferViews", viewIndex);
  if (!view || size == 0) return nullptr;
  const auto viewOffset = unsignedOf(*view, "byteOffset", 0);
  const auto viewLength = unsignedOf(*view, "byteLength", 0);
  if (!viewOffset || !viewLength || !view->contains("buffer")) return nullptr;
  if (count > *viewLength / size || offset > *viewLength - count * size) return nullptr;
  const auto buffer = unsignedOf(*view, "buffer", 0);
  const std::string* bytes = buffer ? buffers.get(*buffer) : nullptr;
  if (!bytes || *viewOffset > bytes->size() || *viewLength > bytes->size() - *viewOffset)
    return nullptr;  // Assimp reports a view past its buffer
  return bytes->data() + *viewOffset + offset;
}

// The index types glTF 2.0 allows (unsigned byte, short, int): 0 for the others, whose bytes are
// no index (gltfElementBytes, io/gltf_layout.h, sizes every component type, signed and float too).
uint64_t indexBytes(uint64_t componentType) {
  return componentType == 5121 ? 1 : componentType == 5123 ? 2 : componentType == 5125 ? 4 : 0;
}

uint32_t indexAt(const char* first, uint64_t i, uint64_t size) {
  uint32_t index = 0;
  std::memcpy(&index, first + i * size, size_t(size));  // little-endian, as glTF stores it
  return index;
}

}  // namespace

std::string glbBinaryChunk(const std::string& bytes) {
  if (bytes.size() < 20) return "";
  const uint64_t next = 20 + ((uint64_t{u32At(bytes, 12)} + 3) & ~uint64_t{3});
  if (next + 8 > bytes.size() || u32At(bytes, size_t(next) + 4) != 0x004E4942u) return "";
  const uint64_t length = u32At(bytes, size_t(next));
  if (next + 8 + length > bytes.size()) return "";
  return bytes.substr(size_t(next) + 8, size_t(length));
}

void checkGltfIndices(const std::string& path, const std::string& gltfJson,
                      const std::string& glbBinary) {
  const json doc = json::parse(gltfJson, nullptr, false);
  if (!doc.is_object()) return;  // gltfSubset has refused it, or will
  Buffers buffers(path, doc, glbBinary);
  // Every embedded buffer is decoded, so that bad base64 is refused whatever reads it.
  if (const auto list = doc.find("buffers"); list != doc.end() && list->is_array())
    for (size_t b = 0; b < list->size(); ++b)
      if (const json& buffer = (*list)[b]; buffer.is_object() &&
                                           buffer.value("uri", json()).is_string() &&
                                           buffer["uri"].get<std::string>().rfind("data:", 0) == 0)
        buffers.get(b);
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return;
  for (size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (primitives == mesh.end() || !primitives->is_array()) continue;
    for (size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      // Only triangles reach Assimp (io/gltf_subset.h): mode 4, the default, 5 and 6.
      const auto mode = primitive.is_object() ? unsignedOf(primitive, "mode", 4) : std::nullopt;
      if (!mode || *mode < 4 || *mode > 6 || !primitive.contains("indices") ||
          !primitive.contains("attributes") || !primitive["attributes"].is_object() ||
          !primitive["attributes"].contains("POSITION"))
        continue;
      const json* positions = gltfElementAt(doc, "accessors", primitive["attributes"]["POSITION"]);
      const json* indices = gltfElementAt(doc, "accessors", primitive["indices"]);
      if (!positions || !indices) continue;
      const auto vertices = unsignedOf(*positions, "count", 0);
      const auto count = unsignedOf(*indices, "count", 0);
      const auto type = unsignedOf(*indices, "componentType", 0);
      const auto offset = unsignedOf(*indices, "byteOffset", 0);
      if (!vertices || !count || !type || !offset) continue;
      const uint64_t size = indexBytes(*type);
      const auto refuse = [&](const std::string& which, uint64_t index) {
        throw GlintError("mesh " + path + ": meshes[" + std::to_string(m) + "].primitives[" +
                         std::to_string(p) + "]: " + which + " = " + std::to_string(index) +
                         ", but its POSITION has " + std::to_string(*vertices) + " vertices");
      };
      // Sparse values replace indices by position (Assimp applied them and dropped the
      // triangles they put out of range, without a word): each value is checked as an index,
      // and the positions they replace are not.
      std::set<uint64_t> replaced;
      const auto sparse = indices->find("sparse");
      if (sparse != indices->end() && sparse->is_object()) {
        const json positionsOf = sparse->value("indices", json());
        const json values = sparse->value("values", json());
        const auto sparseCount = unsignedOf(*sparse, "count", 0);
        const auto positionsOffset =
            positionsOf.is_object() ? unsignedOf(positionsOf, "byteOffset", 0) : std::nullopt;
        const auto positionsType =
            positionsOf.is_object() ? unsignedOf(positionsOf, "componentType", 0) : std::nullopt;
        const auto valuesOffset =
            values.is_object() ? unsignedOf(values, "byteOffset", 0) : std::nullopt;
        if (!sparseCount || !positionsOffset || !positionsType || !valuesOffset ||
            !positionsOf.contains("bufferView") || !values.contains("bufferView"))
          continue;  // malformed: Assimp's to refuse
        const uint64_t positionSize = indexBytes(*positionsType);
        const char* at = viewBytes(doc, buffers, positionsOf["bufferView"], *positionsOffset,
                                   *sparseCount, positionSize);
        const char* value =
            viewBytes(doc, buffers, values["bufferView"], *valuesOffset, *sparseCount, size);
        if (!at || !value) continue;
        for (uint64_t i = 0; i < *sparseCount; ++i) {
          replaced.insert(indexAt(at, i, positionSize));
          if (const uint32_t index = indexAt(value, i, size); index >= *vertices)
            refuse("indices.sparse.values[" + std::to_string(i) + "]", index);
        }
      }
      // An accessor without a view holds zeros until its sparse values replace some.
      if (!indices->contains("bufferView")) continue;
      if (const char* first =
              viewBytes(doc, buffers, (*indices)["bufferView"], *offset, *count, size))
        for (uint64_t i = 0; i < *count; ++i)
          if (const uint32_t index = indexAt(first, i, size);
              index >= *vertices && !replaced.count(i))
            refuse("indices[" + std::to_string(i) + "]", index);
    }
  }
}

}  // namespace glint
