// Where a glTF file's accessors lie in its buffers (io/gltf_layout.h): offsets near 2^64 that
// wrapped Assimp's bounds test (it read memory before the buffer), and accessors without a
// buffer view that made it allocate gigabytes from a file of 840 bytes.
#include "io/gltf_layout.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

#include "core/error.h"

namespace glint {
namespace {

using nlohmann::json;

// A triangle: POSITION (3 floats × 3) in view 0, indices (3 shorts) in view 1, one buffer.
json triangle() {
  return json::parse(R"({
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 44}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})");
}

std::string refusal(const json& doc) {
  try {
    checkGltfBufferLayout("m.gltf", doc);
    return "(accepted)";
  } catch (const UsageError& e) {
    return e.what();
  }
}

TEST(GltfLayout, AccessorsWithinTheirViewsAndViewsWithinTheirBuffersPass) {
  EXPECT_EQ(refusal(triangle()), "(accepted)");
  // Interleaved: a stride of 24 holds the positions' 12 bytes, the last ending at 2·24 + 12.
  json doc = triangle();
  doc["bufferViews"][0]["byteLength"] = 60;
  doc["bufferViews"][0]["byteStride"] = 24;
  doc["buffers"][0]["byteLength"] = 96;
  doc["bufferViews"][1]["byteOffset"] = 60;
  EXPECT_EQ(refusal(doc), "(accepted)");
  // An accessor no triangle reads is not Glint's to judge (a morph target's, dropped).
  doc = triangle();
  doc["accessors"].push_back(json::parse(R"({"componentType": 5126, "count": 1e9,
                                             "type": "VEC3"})"));
  doc["accessors"][2]["count"] = uint64_t{1} << 40;
  EXPECT_EQ(refusal(doc), "(accepted)");
}

TEST(GltfLayout, AttributesMustBeStoredInTypesAssimpReads) {
  // Assimp read a POSITION of SCALAR unsigned shorts, of VEC2 floats or of VEC3 shorts as
  // whatever floats their bytes made: the file rendered, wrong.
  const auto positionAs = [](const char* type, int component, int count) {
    json doc = triangle();
    doc["accessors"][0]["type"] = type;
    doc["accessors"][0]["componentType"] = component;
    doc["accessors"][0]["count"] = count;
    return refusal(doc);
  };
  EXPECT_EQ(positionAs("SCALAR", 5123, 3),
            "mesh m.gltf: meshes[0].primitives[0].attributes.POSITION: accessors[0] is "
            "\"SCALAR\" of componentType 5123; Glint reads POSITION as VEC3 of floats");
  EXPECT_NE(positionAs("VEC2", 5126, 3)
                .find("is \"VEC2\" of componentType 5126; Glint reads "
                      "POSITION as VEC3 of floats"),
            std::string::npos);
  EXPECT_NE(positionAs("VEC3", 5122, 3)
                .find("(integers are KHR_mesh_quantization's, which "
                      "Glint does not read)"),
            std::string::npos);
  // Colours as unsigned integers (Assimp scales them, normalized or not) and texture
  // coordinates as VEC3 (Assimp reads u and v) are read as they should be.
  json doc = triangle();
  doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2u;
  doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 3u;
  doc["accessors"].push_back(json::parse(R"({"bufferView": 0, "componentType": 5126,
                                             "count": 3, "type": "VEC3"})"));
  doc["accessors"].push_back(json::parse(R"({"bufferView": 0, "componentType": 5121,
                                             "count": 2, "type": "VEC4"})"));
  EXPECT_EQ(refusal(doc), "(accepted)");
  doc["accessors"][2]["type"] = "VEC4";
  doc["accessors"][2]["count"] = 2;
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: meshes[0].primitives[0].attributes.TEXCOORD_0: accessors[2] is "
            "\"VEC4\" of componentType 5126; Glint reads TEXCOORD_0 as VEC2 or VEC3 of floats");
  doc["accessors"][2]["type"] = "VEC2";
  doc["accessors"][3]["componentType"] = 5120;  // signed bytes: not a colour glTF allows
  EXPECT_NE(refusal(doc).find("attributes.COLOR_0: accessors[3] is \"VEC4\" of componentType "
                              "5120; Glint reads COLOR_0 as VEC3 or VEC4 of floats or of "
                              "unsigned bytes or shorts"),
            std::string::npos)
      << refusal(doc);
}

TEST(GltfLayout, OffsetsThatWrapPast2To64AreRefused) {
  json doc = triangle();
  doc["bufferViews"][0]["byteOffset"] = UINT64_MAX - 7;  // + 36 wraps to 28
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: bufferViews[0] lies past its buffer: bytes 18446744073709551608 to "
            "past 2^64 of buffers[0]'s 44");
  doc = triangle();
  doc["accessors"][0]["byteOffset"] = UINT64_MAX - 3;
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: accessors[0] reads 3 elements of 12 bytes from byte "
            "18446744073709551612 of bufferViews[0], to byte past 2^64; the view holds 36");
  doc = triangle();
  doc["accessors"][1]["count"] = 4;  // 8 bytes from a view of 6
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: accessors[1] reads 4 elements of 2 bytes from byte 0 of "
            "bufferViews[1], to byte 8; the view holds 6");
}

TEST(GltfLayout, AccessorsWithoutATypeAndImagesViewsAreChecked) {
  // Assimp reads an accessor without a type as SCALAR and one without a componentType as BYTE:
  // an earlier version of the check skipped them, and a wrapped offset read before the buffer.
  json doc = triangle();
  doc["accessors"][0].erase("type");
  doc["bufferViews"][0]["byteOffset"] = UINT64_MAX - 7;
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: accessors[0] has no type and componentType glTF 2.0 defines (null, "
            "5126)");
  // Assimp copies an embedded image out of its buffer view.
  doc = triangle();
  doc["bufferViews"].push_back(json::parse(R"({"buffer": 0, "byteLength": 32})"));
  doc["bufferViews"][2]["byteOffset"] = UINT64_MAX - 15;
  doc["images"] = json::parse(R"([{"bufferView": 2, "mimeType": "image/png"}])");
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: bufferViews[2] lies past its buffer: bytes 18446744073709551600 to "
            "past 2^64 of buffers[0]'s 44");
}

TEST(GltfLayout, StridesGltfDoesNotAllowAreRefused) {
  // byteStride 2^32 − 4 was read as tightly packed.
  for (const uint64_t stride : {uint64_t{2}, uint64_t{254}, uint64_t{13}, uint64_t{4294967292}}) {
    json doc = triangle();
    doc["bufferViews"][0]["byteStride"] = stride;
    EXPECT_EQ(refusal(doc), "mesh m.gltf: bufferViews[0]: its byteStride " +
                                std::to_string(stride) +
                                " is not one glTF 2.0 allows (a multiple of 4 from 4 to 252)");
  }
  json doc = triangle();
  doc["bufferViews"][0]["byteOffset"] = -4;
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: bufferViews[0]: its byteOffset and byteLength must be whole numbers");
}

TEST(GltfLayout, SparseValuesMustLieInTheirViewsAndZerosAreBudgeted) {
  json doc = triangle();
  doc["accessors"][0].erase("bufferView");
  doc["accessors"][0]["sparse"] = json::parse(R"({"count": 2,
      "indices": {"bufferView": 1, "componentType": 5125},
      "values": {"bufferView": 0, "byteOffset": 20}})");
  // Two 4-byte indices from a view of 6; two 12-byte values from byte 20 of a view of 36.
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: accessors[0].sparse.indices reads 2 elements of 4 bytes from byte 0 of "
            "bufferViews[1], to byte 8; the view holds 6");
  doc["accessors"][0]["sparse"]["indices"]["componentType"] = 5123;
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: accessors[0].sparse.values reads 2 elements of 12 bytes from byte 20 "
            "of bufferViews[0], to byte 44; the view holds 36");
  doc["accessors"][0]["sparse"]["values"]["byteOffset"] = 12;
  EXPECT_EQ(refusal(doc), "(accepted)");
  // 2^26 positions of zeros from 840 bytes of glTF took 2.65 GB.
  doc["accessors"][0]["count"] = uint64_t{1} << 26;
  EXPECT_EQ(refusal(doc),
            "mesh m.gltf: accessors[0] has no bufferView and 67108864 elements of 12 bytes: the "
            "accessors without one may hold 67108864 bytes in all (they are zeros but for "
            "their sparse values)");
  doc["accessors"][0]["count"] = kMaxUnbackedAccessorBytes / 12;
  EXPECT_EQ(refusal(doc), "(accepted)");
}

}  // namespace
}  // namespace glint
