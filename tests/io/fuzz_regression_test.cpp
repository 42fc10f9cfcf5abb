// Inputs that once crashed or exhausted the loader, or what reads a loaded scene
// (tests/fuzz/regressions/, docs/hardening.md). Each must load and give a reference BVH that
// keeps its invariants, or be refused with a SceneError that names the file and a line: the
// oracle of tests/fuzz/scene_fuzzer.cpp, for the first frame of an animation.
#include <gtest/gtest.h>

#include <filesystem>

#include "accel/reference_bvh.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kRegressions = fs::path(GLINT_SOURCE_DIR) / "tests/fuzz/regressions";

class FuzzRegression : public testing::TestWithParam<std::string> {};

TEST_P(FuzzRegression, LoadsOrNamesFileAndLine) {
  const std::string name = GetParam();
  const std::string text = test::readFile(kRegressions / name);
  ASSERT_FALSE(text.empty()) << name;
  try {
    // Mesh paths resolve against tests/data, as they do against the fuzzer's copy of it.
    const Scene scene = loadSceneText(text, name, GLINT_TEST_DATA);
    const ReferenceBvh bvh(scene);
    EXPECT_EQ(bvh.checkInvariants(), "") << name;
  } catch (const SceneError& e) {
    EXPECT_GT(e.loc().line, 0) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(name + ":" + std::to_string(e.loc().line) + ": ", 0), 0u)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegression, testing::ValuesIn(test::fileNamesIn(kRegressions)),
                         // Not named `info`: the macro's own parameter has that name.
                         [](const testing::TestParamInfo<std::string>& input) {
                           std::string id = fs::path(input.param).stem().string();
                           for (char& c : id)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return id;
                         });

TEST(FuzzRegression, NestingIsLimitedTo64Levels) {
  // Line 1 opens levels 1–3 (the root, camera, camera.eye). 61 more brackets reach the limit of
  // 64 and load as far as the camera check; one more, on line 3, is the first level too deep.
  const std::string head = "{\"camera\": {\"eye\": [\n" + std::string(61, '[');
  EXPECT_EQ(test::sceneErrorOf(head + std::string(61, ']') + "]}}"),
            "scene.json:1: camera.eye: must be an array of 3 numbers, got " + std::string(62, '[') +
                std::string(62, ']'));
  EXPECT_EQ(test::sceneErrorOf(head + "\n[" + std::string(62, ']') + "]}}"),
            "scene.json:3: arrays and objects nest more than 64 deep (a scene needs at most 8)");
}

TEST(FuzzRegression, KeysAndNamesAreLimitedTo256Characters) {
  const std::string head =
      "{\"camera\": {\"eye\": [0,0,5], \"look_at\": [0,0,0]}, \"objects\": [],\n";
  // 256 characters is allowed: the group loads (unused groups are fine).
  EXPECT_EQ(test::sceneErrorOf(head + "\"groups\": {\"" + std::string(256, 'g') + "\": []}}"),
            "(no error)");
  EXPECT_EQ(test::sceneErrorOf(head + "\"groups\": {\"" + std::string(257, 'g') + "\": []}}"),
            "scene.json:2: a key is 257 characters long; keys and names may have at most 256");
}

TEST(FuzzRegression, ReferenceBvhSeparatesCentroidsNearTheFloatLimit) {
  // Spheres at x = ±3e38: the centroid extent 6e38 overflows float. The build once cast the NaN
  // bin of (c − lo)·B/∞ to int and wrote outside its bins. The camera's central ray from z = 5
  // must still hit the unit sphere at the origin at t = 5 − 1 = 4. The loader now refuses
  // geometry past ±1e18 (next test), so the far spheres are moved there after loading: the BVH
  // must survive any Scene, not only those the loader makes.
  Scene scene = test::sceneFromText(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}}, "objects": [
      {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "m"},
      {"type": "sphere", "center": [-3, 0, 0], "radius": 1, "material": "m"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  scene.spheres[0].center.x = 3e38f;
  scene.spheres[1].center.x = -3e38f;
  const ReferenceBvh bvh(scene);
  EXPECT_EQ(bvh.checkInvariants(), "");
  // The camera's central ray, in whatever frame the loader placed the scene.
  const Camera camera(scene.cameraDesc, scene.render.width, scene.render.height);
  const Ray ray = camera.generateRay(0.5f * static_cast<float>(scene.render.width),
                                     0.5f * static_cast<float>(scene.render.height));
  const Hit hit = bvh.intersect(ray);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
  EXPECT_EQ(scene.groups[0].geometries[hit.geomId].objectId, 2u);
}

}  // namespace
}  // namespace glint
