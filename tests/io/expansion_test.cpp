// Scenes that multiply themselves (glTF nodes shared by several parents, JSON groups placing
// the previous group twice) are counted before anything is placed and refused past their
// budget (io/expansion_limits.h); scenes whose rays would leave Embree's range or whose motion
// has more keys than Embree takes are refused at the JSON path (docs/hardening.md).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/expansion_limits.h"
#include "io/gltf_subset.h"
#include "test_util.h"

namespace glint {
namespace {

using nlohmann::json;

// A glTF file whose node `levels` lists node `levels − 1` twice, down to node 0, which places
// one triangle of `vertices` declared vertices (3: the one the buffer holds).
std::string sharedChildrenGltf(int levels, uint64_t vertices = 3) {
  json nodes = json::array({{{"mesh", 0}}});
  for (int i = 1; i <= levels; ++i) nodes.push_back({{"children", {i - 1, i - 1}}});
  const std::string triangle = std::string("\0\0\0\0\0\0\0\0\0\0\0\0", 12) +
                               std::string("\0\0\x80\x3f\0\0\0\0\0\0\0\0", 12) +
                               std::string("\0\0\0\0\0\0\x80\x3f\0\0\0\0", 12);
  return json{{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", {levels}}}}},
              {"nodes", nodes},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
              {"accessors",
               {{{"bufferView", 0},
                 {"componentType", 5126},
                 {"count", vertices},
                 {"type", "VEC3"},
                 {"min", {0, 0, 0}},
                 {"max", {1, 1, 0}}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
              {"buffers",
               {{{"byteLength", 36},
                 {"uri", "data:application/octet-stream;base64," + test::base64(triangle)}}}}}
      .dump();
}

TEST(Expansion, SaturatingCountsHoldAtTheTopInsteadOfWrapping) {
  // 2^32 · 2^32 = 2^64 does not fit: held at 2^64 − 1, which reads as "more than 2^64 − 2".
  EXPECT_EQ(saturatingMul(uint64_t{1} << 32, uint64_t{1} << 32), UINT64_MAX);
  EXPECT_EQ(saturatingMul(uint64_t{1} << 31, uint64_t{1} << 32), uint64_t{1} << 63);
  EXPECT_EQ(saturatingAdd(UINT64_MAX - 1, 2), UINT64_MAX);
  EXPECT_EQ(countText(UINT64_MAX), "more than 18446744073709551614");
  // Past 8 names the middle is left out, 4 kept at each end.
  EXPECT_EQ(pathText({"a", "b", "c", "d", "e", "f", "g", "h", "i", "j"}),
            "a > b > c > d > … (2 more) > g > h > i > j");
}

TEST(Expansion, AGltfNodeListingAChildTwiceFortyDeepIsRefusedBeforeItIsWalked) {
  // 40 levels of doubling: 2^0 + … + 2^40 = 2^41 − 1 node copies. Once this spun `glint
  // render` and `info` for ever and grew Assimp to 3.85 GB; now counted in time linear in the
  // 41 nodes (tests/fuzz/regressions-mesh/gltf-shared-children-40-levels-hang.bin).
  const std::string error = test::meshLoadError("shared40.gltf", sharedChildrenGltf(40));
  EXPECT_NE(error.find("scenes[0] flattens to 2199023255551 node copies, more than the 1048576"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("most come through nodes[40] > nodes[39] > nodes[38] > nodes[37] > … "
                       "(33 more) > nodes[3] > nodes[2] > nodes[1] > nodes[0]"),
            std::string::npos)
      << error;
  // The same file through a JSON scene's "file" names the scene's key too, exit 2 (a UsageError).
  test::writeTemp("shared40.gltf", sharedChildrenGltf(40));
  try {
    loadSceneText(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
      "objects": [{"type": "mesh", "file": "shared40.gltf"}]})",
                  "scene.json", test::tempDir().string());
    ADD_FAILURE() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "objects[0].file");
  }
}

TEST(Expansion, SharedGltfNodesWithinTheBudgetLoadEveryCopy) {
  // 10 levels: 2^10 = 1024 copies of the one triangle, which Assimp places once per path.
  const std::string path = test::writeTemp("shared10.gltf", sharedChildrenGltf(10));
  const MeshFile file = loadMeshFile(path);
  ASSERT_EQ(file.parts.size(), 1u);
  EXPECT_EQ(file.parts[0].indices.size(), 3u * 1024);
}

TEST(Expansion, GltfTrianglesAreCountedFromTheAccessorsBeforeAnyBufferIsRead) {
  // 4 levels (16 copies) of a primitive declaring 3 · 2^20 vertices: 16 · 2^20 = 2^24 triangles,
  // the budget exactly, passes the count (and then fails where Assimp finds the buffer short);
  // 5 levels, 2^25, is refused by the count, before the buffer is read.
  const std::string within = test::meshLoadError("tris4.gltf", sharedChildrenGltf(4, 3u << 20));
  EXPECT_EQ(within.find("flattens to"), std::string::npos) << within;
  const std::string past = test::meshLoadError("tris5.gltf", sharedChildrenGltf(5, 3u << 20));
  EXPECT_NE(past.find("scenes[0] flattens to 33554432 triangles, more than the 16777216"),
            std::string::npos)
      << past;
}

TEST(Expansion, AGltfNodeGraphWithACycleOrAMissingChildIsRefused) {
  json doc = json::parse(sharedChildrenGltf(2));
  doc["nodes"][0]["children"] = {2};  // 2 → 1 → 0 → 2
  EXPECT_NE(test::meshLoadError("cycle.gltf", doc.dump())
                .find("nodes[2] is its own ancestor (the node tree has a cycle)"),
            std::string::npos);
  doc["nodes"][0]["children"] = {7};
  EXPECT_NE(test::meshLoadError("missing.gltf", doc.dump())
                .find("nodes[0].children names nodes[7], which does not exist (3 nodes)"),
            std::string::npos);
}

TEST(Expansion, AGltfNodeScaledPastTheRayRangeIsNamed) {
  // The triangle (0..2 in x and y) under a scale of 1e38 lies at 2e38. Once this said "up is
  // parallel to the viewing direction" (the camera framed infinite bounds).
  json doc = json::parse(test::readFile(std::string(GLINT_TEST_DATA) + "/triangle.gltf"));
  doc["nodes"][0]["scale"] = {1e38, 1e38, 1e38};
  doc["nodes"][0]["name"] = "Huge";
  const std::string error = test::meshLoadError("huge.gltf", doc.dump());
  EXPECT_NE(error.find("node \"Huge\" places a vertex at 2e+38 along an axis (its transform "
                       "composed with its parents' scales by up to 1e+38"),
            std::string::npos)
      << error;
}

const std::string kMaterial = R"("materials": {"m": {"type": "phong"}})";

// Groups g1 … g`levels`, each placing the one before twice; g0 holds a sphere.
std::string doublingGroups(int levels) {
  std::string groups =
      R"("g0": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}])";
  for (int i = 1; i <= levels; ++i) {
    const std::string previous = "\"g" + std::to_string(i - 1) + "\"";
    groups += ",\n\"g" + std::to_string(i) +
              "\": [{\"type\": \"instance\", \"group\": " + previous +
              "}, {\"type\": \"instance\", \"group\": " + previous + "}]";
  }
  return groups;
}

TEST(Expansion, JsonGroupsDoublingFortyDeepAreRefusedBeforeAnyIsPlaced) {
  // 2^40 world-level instances of g0's sphere: once 1.5–2.9 GB before "out of memory"
  // (tests/fuzz/regressions/groups-doubling-40-levels.json).
  const std::string error = test::sceneErrorOf(
      "{\"camera\": {\"eye\": [0,0,5], \"look_at\": [0,0,0]}, " + kMaterial +
      ",\n"
      "\"objects\": [{\"type\": \"instance\", \"group\": \"g40\"}],\n\"groups\": {" +
      doublingGroups(40) + "}}");
  EXPECT_EQ(error.rfind("scene.json:2: objects[0]: this instance of group \"g40\" places "
                        "1099511627776 instances",
                        0),
            0u)
      << error;
  EXPECT_NE(error.find("more than the 1048576 a scene may have; most come through \"g40\" > "
                       "\"g39\" > \"g38\" > \"g37\" > … (33 more) > \"g3\" > \"g2\" > \"g1\" > "
                       "\"g0\""),
            std::string::npos)
      << error;
}

TEST(Expansion, TheInstanceBudgetCountsWhatIsAlreadyPlaced) {
  // g20 places 2^20 instances, the budget exactly; after one sphere instance placed by g0 the
  // total is 2^20 + 1, one too many, refused before any of g20's is placed.
  const std::string error = test::sceneErrorOf(
      "{\"camera\": {\"eye\": [0,0,5], \"look_at\": [0,0,0]}, " + kMaterial +
      ",\n\"objects\": [\n"
      "{\"type\": \"instance\", \"group\": \"g0\"},\n{\"type\": \"instance\", \"group\": "
      "\"g20\"}],\n\"groups\": {" +
      doublingGroups(20) + "}}");
  EXPECT_EQ(error.rfind("scene.json:4: objects[1]: this instance of group \"g20\" places 1048576 "
                        "instances",
                        0),
            0u)
      << error;
  EXPECT_NE(error.find("after the 1 already placed, more than the 1048576"), std::string::npos)
      << error;
}

TEST(Expansion, MotionKeysBeyondEmbreesTimeStepsAreRefusedAtTheirPath) {
  // Embree's RTC_MAX_TIME_STEP_COUNT is 129: 129 keys load, 130 once ended as a bare
  // "Embree error 2" with exit 1.
  const auto scene = [](int keys) {
    std::string centers;
    for (int k = 0; k < keys; ++k)
      centers += (k ? ", [0, 0, " : "[0, 0, ") + std::to_string(k) + "]";
    return "{\"camera\": {\"eye\": [0,0,500], \"look_at\": [0,0,0], \"shutter\": [0, 1]}, " +
           kMaterial +
           ",\n\"objects\": [{\"type\": \"sphere\", \"radius\": 1, \"material\": \"m\",\n"
           "\"motion\": {\"center\": [" +
           centers + "]}}]}";
  };
  EXPECT_EQ(test::sceneErrorOf(scene(129)), "(no error)");
  EXPECT_EQ(test::sceneErrorOf(scene(130)),
            "scene.json:3: objects[0].motion.center: lists 130 keys; an object may move through "
            "at most 129 in a frame (Embree's limit, RTC_MAX_TIME_STEP_COUNT; an animation's keys "
            "are resampled for each frame)");
}

TEST(Expansion, CameraWindowsAndGeometryPastTheRayRangeAreRefused) {
  // Each window value is a float, but r − l = 4e38 is not: camera rays were NaN and Embree's
  // assertion aborted render, validate, bench and converge.
  EXPECT_EQ(test::sceneErrorOf(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0],
    "window": [-2e38, 2e38, -1, 1]}, "objects": []})"),
            "scene.json:2: camera.window[0]: window values must lie within ±1e18 (the range of "
            "rays Glint traces; r − l and t − b must be floats)");
  // ±1e18 itself is within the range.
  EXPECT_EQ(test::sceneErrorOf(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0],
    "window": [-1e18, 1e18, -1, 1]}, "objects": []})"),
            "(no error)");
  // An orthographic height of 3e38 gives a window of ±1.5e38 (derived, so named at the camera).
  EXPECT_EQ(test::sceneErrorOf(R"({"camera": {"type": "orthographic", "eye": [0,0,5],
    "look_at": [0,0,0], "height": 3e38}, "objects": []})"),
            "scene.json:1: camera: the image window [-1.5e+38, 1.5e+38, -1.5e+38, 1.5e+38] "
            "reaches past ±1e18, beyond the range of rays Glint traces");
  // A sphere reaching 1.9e20 from the camera: rays leaving its surface would start past
  // Embree's 1.844e18.
  EXPECT_EQ(test::sceneErrorOf(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,-1e20], "radius": 9e19, "material": "m"}]})"),
            "scene.json:3: objects[0]: reaches past ±1e18 from the camera, beyond the range of "
            "rays Glint traces");
}

}  // namespace
}  // namespace glint
