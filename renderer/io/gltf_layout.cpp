#include "io/gltf_layout.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/expansion_limits.h"

namespace glint {

namespace {

using nlohmann::json;

// `key` of `object` as a whole number, `otherwise` where it is absent; nullopt where it is not
// a whole number (a negative, fractional or other value).
std::optional<uint64_t> wholeOf(const json& object, const char* key,
                                std::optional<uint64_t> otherwise) {
  const auto it = object.find(key);
  if (it == object.end()) return otherwise;
  if (it->is_number_unsigned()) return it->get<uint64_t>();
  if (it->is_number_integer() && it->get<int64_t>() >= 0) return uint64_t(it->get<int64_t>());
  return std::nullopt;
}

uint64_t componentBytes(const json& componentType) {
  if (!componentType.is_number_integer()) return 0;
  switch (componentType.get<int64_t>()) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

class LayoutCheck {
 public:
  LayoutCheck(const std::string& path, const json& doc) : path_(path), doc_(doc) {}

  // The buffer views of embedded images, which Assimp copies out of their buffers.
  void imageViews() const {
    const auto images = doc_.find("images");
    if (images == doc_.end() || !images->is_array()) return;
    for (const json& image : *images) {
      if (!image.is_object() || !image.contains("bufferView")) continue;
      const json& index = image["bufferView"];
      if (const json* view = gltfElementAt(doc_, "bufferViews", index)) viewFits(index, *view);
    }
  }

  // That each attribute Glint reads is stored as glTF 2.0 allows (its §3.7.2.1): Assimp read
  // a POSITION of SCALAR shorts, or of VEC2 floats, as whatever floats its bytes made.
  void attributeTypes() const {
    const auto meshes = doc_.find("meshes");
    if (meshes == doc_.end() || !meshes->is_array()) return;
    for (size_t m = 0; m < meshes->size(); ++m) {
      const json& mesh = (*meshes)[m];
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
        continue;
      for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
        const json& primitive = mesh["primitives"][p];
        const auto a = primitive.is_object() ? primitive.find("attributes") : primitive.end();
        if (a == primitive.end() || !a->is_object()) continue;
        for (const auto& [name, index] : a->items()) {
          const json* accessor = gltfElementAt(doc_, "accessors", index);
          if (!accessor) continue;  // Assimp names it
          attributeType("meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) +
                            "].attributes." + name,
                        name, index, *accessor);
        }
      }
    }
  }

  // The accessors the file's triangles read, and the bytes of those without a buffer view.
  void accessors() const {
    std::set<uint64_t> read;
    const auto meshes = doc_.find("meshes");
    if (meshes != doc_.end() && meshes->is_array())
      for (const json& mesh : *meshes)
        if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
          for (const json& primitive : mesh["primitives"]) {
            if (!primitive.is_object()) continue;
            if (const auto it = primitive.find("indices");
                it != primitive.end() && it->is_number_unsigned())
              read.insert(it->get<uint64_t>());
            if (const auto a = primitive.find("attributes"); a != primitive.end() && a->is_object())
              for (const json& index : *a)
                if (index.is_number_unsigned()) read.insert(index.get<uint64_t>());
          }
    uint64_t unbacked = 0;
    for (const uint64_t i : read) {
      const json* accessor = gltfElementAt(doc_, "accessors", json(i));
      if (!accessor) continue;  // Assimp names it
      const std::string where = "accessors[" + std::to_string(i) + "]";
      const uint64_t element = gltfElementBytes(*accessor);
      if (element == 0)
        fail(where + " has no type and componentType glTF 2.0 defines (" +
             accessor->value("type", json()).dump() + ", " +
             accessor->value("componentType", json()).dump() + ")");
      const auto count = wholeOf(*accessor, "count", std::nullopt);
      if (!count) continue;  // Assimp refuses it
      if (accessor->contains("bufferView")) {
        fitsInView(where, *accessor, *count, element, true);
      } else {
        unbacked = saturatingAdd(unbacked, saturatingMul(*count, element));
        if (unbacked > kMaxUnbackedAccessorBytes)
          fail(where + " has no bufferView and " + std::to_string(*count) + " elements of " +
               std::to_string(element) + " bytes: the accessors without one may hold " +
               std::to_string(kMaxUnbackedAccessorBytes) +
               " bytes in all (they are zeros but for their sparse values)");
      }
      const auto sparse = accessor->find("sparse");
      if (sparse == accessor->end() || !sparse->is_object()) continue;
      const auto sparseCount = wholeOf(*sparse, "count", std::nullopt);
      if (!sparseCount) continue;
      if (const auto indices = sparse->find("indices");
          indices != sparse->end() && indices->is_object()) {
        const uint64_t indexBytes = componentBytes(indices->value("componentType", json()));
        if (indexBytes == 0) fail(where + ".sparse.indices has no componentType glTF 2.0 defines");
        fitsInView(where + ".sparse.indices", *indices, *sparseCount, indexBytes, false);
      }
      if (const auto values = sparse->find("values");
          values != sparse->end() && values->is_object())
        fitsInView(where + ".sparse.values", *values, *sparseCount, element, false);
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw UsageError("mesh " + path_ + ": " + what);
  }

  // The types Assimp reads the attribute `name` in as glTF 2.0 gives them: floats, and for
  // colours unsigned bytes and shorts too (which Assimp scales to [0, 1], normalized or not).
  // Texture coordinates stored as integers were dropped before (gltf_subset.cpp), and VEC3
  // ones pass: Assimp reads their u and v. Attributes glTF leaves open (_NAME) pass.
  void attributeType(const std::string& where, const std::string& name, const json& index,
                     const json& accessor) const {
    const auto startsWith = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
    std::vector<std::string> types;
    bool integerColours = false;
    if (name == "POSITION" || name == "NORMAL") {
      types = {"VEC3"};
    } else if (name == "TANGENT") {
      types = {"VEC4"};
    } else if (startsWith("TEXCOORD_")) {
      types = {"VEC2", "VEC3"};
    } else if (startsWith("COLOR_")) {
      types = {"VEC3", "VEC4"};
      integerColours = true;
    } else {
      return;
    }
    const std::string type = accessor.value("type", json()).is_string()
                                 ? accessor["type"].get<std::string>()
                                 : std::string();
    const json& component = accessor.value("componentType", json());
    const int64_t c = component.is_number_integer() ? component.get<int64_t>() : 0;
    const bool typeOk = std::find(types.begin(), types.end(), type) != types.end();
    const bool componentOk = c == 5126 || (integerColours && (c == 5121 || c == 5123));
    if (typeOk && componentOk) return;
    std::string allowed = types[0];
    for (size_t i = 1; i < types.size(); ++i) allowed += " or " + types[i];
    allowed += " of floats";
    if (integerColours) allowed += " or of unsigned bytes or shorts";
    if (typeOk && !integerColours && c >= 5120 && c <= 5125)
      allowed += " (integers are KHR_mesh_quantization's, which Glint does not read)";
    fail(where + ": accessors[" + index.dump() + "] is " +
         excerpt(accessor.value("type", json()).dump()) + " of componentType " +
         excerpt(component.dump()) + "; Glint reads " + name + " as " + allowed);
  }

  static std::string sumText(uint64_t a, uint64_t b) {
    return a > UINT64_MAX - b ? "past 2^64" : std::to_string(a + b);
  }

  // That buffer view `index` lies within its buffer, with a stride glTF allows.
  void viewFits(const json& index, const json& view) const {
    const std::string where = "bufferViews[" + index.dump() + "]";
    const auto offset = wholeOf(view, "byteOffset", 0);
    const auto length = wholeOf(view, "byteLength", std::nullopt);
    if (!offset || !length) fail(where + ": its byteOffset and byteLength must be whole numbers");
    if (const auto stride = wholeOf(view, "byteStride", 4);
        !stride || *stride < 4 || *stride > 252 || *stride % 4 != 0)
      fail(where + ": its byteStride " + view["byteStride"].dump() +
           " is not one glTF 2.0 allows (a multiple of 4 from 4 to 252)");
    const json* buffer = gltfElementAt(doc_, "buffers", view.value("buffer", json()));
    if (!buffer) return;  // Assimp names the missing buffer
    const auto bufferLength = wholeOf(*buffer, "byteLength", std::nullopt);
    if (bufferLength && (*offset > *bufferLength || *length > *bufferLength - *offset))
      fail(where + " lies past its buffer: bytes " + std::to_string(*offset) + " to " +
           sumText(*offset, *length) + " of buffers[" + view["buffer"].dump() + "]'s " +
           std::to_string(*bufferLength));
  }

  // That `count` elements of `element` bytes from `reader`'s byteOffset lie within its buffer
  // view, and the view within its buffer: strided by the view's byteStride where `strided` and
  // the view has one, else packed.
  void fitsInView(const std::string& where, const json& reader, uint64_t count, uint64_t element,
                  bool strided) const {
    if (count == 0 || element == 0) return;
    const json& index = reader.value("bufferView", json());
    const json* view = gltfElementAt(doc_, "bufferViews", index);
    if (!view) return;  // Assimp names it
    viewFits(index, *view);
    const auto offset = wholeOf(reader, "byteOffset", 0);
    const uint64_t length = *wholeOf(*view, "byteLength", std::nullopt);
    if (!offset) fail(where + ": its byteOffset must be a whole number");
    const uint64_t step = strided ? *wholeOf(*view, "byteStride", element) : element;
    // The last element's end, offset + (count − 1)·step + element, without wrapping.
    const uint64_t end =
        saturatingAdd(saturatingAdd(*offset, saturatingMul(count - 1, step)), element);
    if (end > length)
      fail(where + " reads " + std::to_string(count) + " elements of " + std::to_string(element) +
           " bytes from byte " + std::to_string(*offset) + " of bufferViews[" +
           reader["bufferView"].dump() + "], to byte " +
           (end == UINT64_MAX ? std::string("past 2^64") : std::to_string(end)) +
           "; the view holds " + std::to_string(length));
  }

  const std::string& path_;
  const json& doc_;
};

}  // namespace

const json* gltfElementAt(const json& doc, const char* list, const json& index) {
  const auto it = doc.find(list);
  if (it == doc.end() || !it->is_array() || !index.is_number_unsigned() ||
      index.get<uint64_t>() >= it->size())
    return nullptr;
  const json& e = (*it)[index.get<size_t>()];
  return e.is_object() ? &e : nullptr;
}

uint64_t gltfElementBytes(const json& accessor) {
  const auto type = accessor.find("type");
  if (type == accessor.end() || !type->is_string()) return 0;
  const std::string& s = type->get_ref<const std::string&>();
  const uint64_t components = s == "SCALAR"                ? 1
                              : s == "VEC2"                ? 2
                              : s == "VEC3"                ? 3
                              : s == "VEC4" || s == "MAT2" ? 4
                              : s == "MAT3"                ? 9
                              : s == "MAT4"                ? 16
                                                           : 0;
  return components * componentBytes(accessor.value("componentType", json()));
}

void checkGltfBufferLayout(const std::string& path, const json& doc) {
  const LayoutCheck check(path, doc);
  check.accessors();
  check.attributeTypes();
  check.imageViews();
}

}  // namespace glint
