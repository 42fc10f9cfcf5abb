// Names reach what a compositor reads (docs/output.md): rendered frames decoded as Cryptomatte
// and Blender's object index are read, with the manifests naming each id, and the layers of
// named lights' AOVs.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "gltf_util.h"
#include "render/crypto_decoder.h"
#include "test_util.h"

namespace glint {
namespace {

using json = nlohmann::json;
using test::bitsOf;

// Renders `scene` (written as NAME.json) with `aovs` and reads the frame back.
test::CryptoFile render(const std::string& name, const std::string& scene, const std::string& aovs,
                        const std::string& extra = "") {
  const std::string path = test::writeTemp(name + ".json", scene);
  const std::string out = (test::tempDir() / (name + ".exr")).string();
  const test::RunResult r =
      test::runGlint("render " + path + " --quiet -o " + out + " --aov " + aovs + " " + extra);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return test::readCryptoFile(out);
}

// Looking down −z, orthographic, one pixel per unit: pixel k spans x ∈ [k − 1, k], y ∈ [0, 1].
// 16 regular samples per pixel, none on a pixel's edge.
const char* kFrame = R"(
  "render": {"width": 4, "height": 1, "spp": 16, "sampler": "regular"},
  "camera": {"type": "orthographic", "eye": [1,0.5,5], "look_at": [1,0.5,0], "height": 1},
  "materials": {"red": {"type": "phong", "kd": [0.5,0,0], "ks": [0,0,0]}},)";

TEST(ObjectNames, ANamedObjectIsItsNameInBothManifestsAndItsPixels) {
  // Ball covers pixel 1 (x ∈ [0, 1]) whole, the unnamed quad pixel 3 (x ∈ [2, 3]).
  const std::string scene = std::string("{") + kFrame + R"(
    "objects": [
      {"type": "quad", "name": "Ball", "corner": [0,-1,0], "edge1": [1,0,0], "edge2": [0,3,0],
       "material": "red"},
      {"type": "quad", "corner": [2,-1,0], "edge1": [1,0,0], "edge2": [0,3,0],
       "material": "red"}]})";
  const std::string stats = (test::tempDir() / "named_ball.stats.json").string();
  const test::CryptoFile f =
      render("named_ball", scene, "cryptomatte,objectid", "--stats-json " + stats);
  const test::CryptoType objects = test::findType(f, "CryptoObject");
  // MurmurHash3_x86_32("Ball", seed 0) = 0x74d3ebe9 (a normal float's bits: kept as they are),
  // computed apart from Glint by the algorithm's reference code.
  ASSERT_EQ(objects.manifest.count("Ball"), 1u);
  EXPECT_EQ(objects.manifest.at("Ball"), 0x74d3ebe9u);
  EXPECT_EQ(objects.manifest.size(), 2u);  // Ball and objects[1]
  EXPECT_EQ(objects.coverage(f, 1, 0x74d3ebe9u), 1.0);
  EXPECT_EQ(objects.coverage(f, 3, objects.manifest.at("objects[1]")), 1.0);
  EXPECT_EQ(objects.coverage(f, 3, 0x74d3ebe9u), 0.0);
  // Blender's object index: Ball is 1, the quad 2, the background 0; the manifest names them.
  EXPECT_EQ(f.channels.at("IndexOB.X"), (std::vector<float>{0, 1, 0, 2}));
  EXPECT_EQ(json::parse(f.attributes.at("glint:objectid_manifest")),
            json::parse(R"({"1": "Ball", "2": "objects[1]"})"));
  // --stats-json lists the objects by the same ids.
  EXPECT_EQ(json::parse(test::readFile(stats)).at("objects"),
            json::parse(R"([{"id": 1, "name": "Ball"}, {"id": 2, "name": "objects[1]"}])"));
}

// Two unit squares, Left at x ∈ [0, 1] and Right at x ∈ [2, 3] (y ∈ [0, 1]), of one material.
std::string twoSquaresGltf() {
  json doc = json::parse(test::gltfSquares({0, 0}, R"([{"name": "paint"}])"));
  doc["nodes"][0]["name"] = "Left";
  doc["nodes"][1]["name"] = "Right";
  doc.erase("textures");
  doc.erase("images");
  return doc.dump();
}

TEST(ObjectNames, AMeshFilesNamedNodesAreObjectsWhereTheyAre) {
  test::writeTemp("two_nodes.gltf", twoSquaresGltf());
  test::writeTemp("two_objects.obj",
                  "o Left\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
                  "o Right\nv 2 0 0\nv 3 0 0\nv 3 1 0\nv 2 1 0\nf 5 6 7 8\n");
  for (const std::string file : {"two_nodes.gltf", "two_objects.obj"}) {
    SCOPED_TRACE(file);
    const test::CryptoFile f = render(
        "two_" + file.substr(file.size() - 3),
        std::string("{") + kFrame + R"("objects": [{"type": "mesh", "file": ")" + file + R"("}]})",
        "cryptomatte,objectid");
    const test::CryptoType objects = test::findType(f, "CryptoObject");
    // Hashes as above: "Left" 0x63a5d310, "Right" 0x8eb27afa.
    EXPECT_EQ(objects.manifest,
              (std::map<std::string, uint32_t>{{"Left", 0x63a5d310u}, {"Right", 0x8eb27afau}}));
    EXPECT_EQ(objects.coverage(f, 1, 0x63a5d310u), 1.0);
    EXPECT_EQ(objects.coverage(f, 1, 0x8eb27afau), 0.0);
    EXPECT_EQ(objects.coverage(f, 3, 0x8eb27afau), 1.0);
    EXPECT_EQ(objects.coverage(f, 3, 0x63a5d310u), 0.0);
    EXPECT_EQ(objects.coverage(f, 0, 0x63a5d310u) + objects.coverage(f, 2, 0x63a5d310u), 0.0);
    EXPECT_EQ(f.channels.at("IndexOB.X"), (std::vector<float>{0, 1, 0, 2}));
    EXPECT_EQ(json::parse(f.attributes.at("glint:objectid_manifest")),
              json::parse(R"({"1": "Left", "2": "Right"})"));
  }
}

TEST(ObjectNames, ANamedLightsAovCarriesItsName) {
  // A diffuse quad (k_d 0.5) facing two directional lights head on: the named one of intensity
  // 1 gives it 0.5 · 1 · cos 0 = 0.5, the unnamed one of 0.25 gives 0.125.
  const std::string scene = std::string("{") + kFrame + R"(
    "lights": [{"type": "directional", "name": "Key Light", "direction": [0,0,-1]},
               {"type": "directional", "direction": [0,0,-1], "intensity": [0.25,0.25,0.25]}],
    "objects": [{"type": "quad", "corner": [-1,-1,0], "edge1": [4,0,0], "edge2": [0,3,0],
                 "material": "red"}]})";
  const test::CryptoFile f = render("named_light", scene, "lights");
  ASSERT_EQ(f.channels.count("light_Key_Light.R"), 1u);
  ASSERT_EQ(f.channels.count("light1.R"), 1u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(f.channels.at("light_Key_Light.R")[i], 0.5, 1e-6) << i;
    EXPECT_NEAR(f.channels.at("light1.R")[i], 0.125, 1e-6) << i;
  }
  EXPECT_EQ(json::parse(f.attributes.at("glint:light_layers")),
            json::parse(R"({"light_Key_Light": "Key Light", "light1": "lights[1]"})"));
}

TEST(ObjectNames, AGltfsLightsKeepTheirNamesOnceEach) {
  // Two KHR_lights_punctual lights both named "Sun": the second is numbered as Blender numbers
  // a copy.
  json doc = json::parse(twoSquaresGltf());
  doc["extensionsUsed"].push_back("KHR_lights_punctual");
  doc["extensions"]["KHR_lights_punctual"]["lights"] =
      json::parse(R"([{"type": "directional", "name": "Sun"}, {"type": "point", "name": "Sun"}])");
  for (int i = 0; i < 2; ++i) {
    json node = {{"translation", {0.0, 0.0, 3.0}}};
    node["extensions"]["KHR_lights_punctual"]["light"] = i;
    doc["scenes"][0]["nodes"].push_back(doc["nodes"].size());
    doc["nodes"].push_back(node);
  }
  const std::string gltf = test::writeTemp("named_lights.gltf", doc.dump());
  const std::string stats = (test::tempDir() / "named_lights.stats.json").string();
  const test::RunResult r =
      test::runGlint("render " + gltf + " --quiet --width 8 --height 8 " + "--spp 1 -o " +
                     (test::tempDir() / "nl.exr").string() + " --stats-json " + stats);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json j = json::parse(test::readFile(stats));
  EXPECT_EQ(j.at("lights"), json::parse(R"(["Sun", "Sun.001"])"));
  EXPECT_EQ(j.at("objects"),
            json::parse(R"([{"id": 1, "name": "Left"}, {"id": 2, "name": "Right"}])"));
}

}  // namespace
}  // namespace glint
