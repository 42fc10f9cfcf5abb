#pragma once
// glTF files the tests write.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "test_util.h"

namespace glint::test {

// A glTF file of unit squares at z = 0, square i at x ∈ [2i, 2i + 1] drawn with material
// `materialOf[i]` of `materials` (a JSON array); glTF's u = x − 2i and v = 1 − y (v runs down
// the image, so the image stands upright on the square); texture 0 is the file `image`.
inline std::string gltfSquares(const std::vector<int>& materialOf, const std::string& materials,
                               const std::string& image = "regions.png") {
  using nlohmann::json;
  const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float uvs[8] = {0, 1, 1, 1, 1, 0, 0, 0};
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
  buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
  json nodes = json::array(), meshes = json::array(), scene = json::object();
  for (size_t i = 0; i < materialOf.size(); ++i) {
    json node = json::object(), primitive = json::object();
    node["mesh"] = i;
    node["translation"] = json::array({2.0 * double(i), 0.0, 0.0});
    nodes.push_back(node);
    primitive["attributes"] = json::parse(R"({"POSITION": 0, "TEXCOORD_0": 1})");
    primitive["indices"] = 2;
    primitive["material"] = materialOf[i];
    meshes.push_back(json::object());
    meshes.back()["primitives"] = json::array({primitive});
    scene["nodes"].push_back(i);
  }
  return R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_texture_transform"],
    "scene": 0, "scenes": [)" +
         scene.dump() + R"(], "nodes": )" + nodes.dump() + R"(, "meshes": )" + meshes.dump() +
         R"(, "materials": )" + materials + R"(,
    "textures": [{"source": 0}], "images": [{"uri": ")" +
         image + R"("}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
    "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
}

}  // namespace glint::test
