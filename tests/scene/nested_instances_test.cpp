// Nested instancing (issue 23): groups hold instances of groups, any depth, as a glTF node tree
// needs. Debian's Embree has one instance level, so the loader flattens the tree into
// world-level instances with composed transforms (io/object_loader.cpp placeGroup); the
// reference BVH and brute force see the same flattened scene.
#include <gtest/gtest.h>

#include "accel/accelerator.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

const char* kHeader = R"({
  "render": {"width": 48, "height": 32, "spp": 2},
  "camera": {"eye": [0, 3, 9], "look_at": [0, 0.5, 0]},
  "materials": {"m": {"type": "phong", "kd": [0.7, 0.5, 0.3], "ks": [0.3, 0.3, 0.3]}},
  "lights": [{"type": "point", "position": [3, 6, 4], "intensity": [1, 1, 1]}],)";

// Three levels: "quad" holds two "pair"s 3 units apart, each holding two "leaf" spheres and a
// box of its own; the world places "quad" scaled 2, turned 90° about y, raised 1.
const std::string kNested = std::string(kHeader) + R"(
  "groups": {
    "leaf": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.4, "material": "m"}],
    "pair": [{"type": "instance", "group": "leaf", "transform": {"translate": [-1, 0, 0]}},
             {"type": "instance", "group": "leaf", "transform": {"translate": [1, 0, 0]}},
             {"type": "box", "min": [-0.2, -0.2, -0.2], "max": [0.2, 0.2, 0.2], "material": "m"}],
    "quad": [{"type": "instance", "group": "pair", "transform": {"translate": [0, 0, -1.5]}},
             {"type": "instance", "group": "pair", "transform": {"translate": [0, 0, 1.5]}}]},
  "objects": [{"type": "instance", "group": "quad",
               "transform": {"scale": [2, 2, 2], "rotate": [0, 1, 0, 90], "translate": [0, 1, 0]}}]})";

// The same by hand: T(0,1,0)·R_y(90°)·S(2) composed with T(x, 0, z) is scale 2, the same turn,
// and translation (0, 1, 0) + R(2x, 0, 2z) = (2z, 1, −2x).
std::string placed(const char* group, double x, double z) {
  return R"({"type": "instance", "group": ")" + std::string(group) +
         R"(", "transform": {"scale": [2, 2, 2], "rotate": [0, 1, 0, 90], "translate": [)" +
         std::to_string(2 * z) + ", 1, " + std::to_string(-2 * x) + "]}}";
}
const std::string kFlattened = std::string(kHeader) + R"(
  "groups": {
    "leaf": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.4, "material": "m"}],
    "box": [{"type": "box", "min": [-0.2, -0.2, -0.2], "max": [0.2, 0.2, 0.2], "material": "m"}]},
  "objects": [)" + placed("box", 0, -1.5) +
                               "," + placed("leaf", -1, -1.5) + "," + placed("leaf", 1, -1.5) +
                               "," + placed("box", 0, 1.5) + "," + placed("leaf", -1, 1.5) + "," +
                               placed("leaf", 1, 1.5) + "]}";

Film renderWith(const std::string& text, AccelKind kind) {
  const Scene scene = test::sceneFromText(text);
  const auto accel = makeAccelerator(kind, scene);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(scene, *accel, opt).film;
}

TEST(NestedInstances, EqualTheSceneFlattenedByHand) {
  const Scene nested = test::sceneFromText(kNested);
  // Two pairs, each its box's instance and two leaves': six world-level instances.
  EXPECT_EQ(nested.instances.size(), 6u);
  for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
    const Film a = renderWith(kNested, kind), b = renderWith(kFlattened, kind);
    // Bit for bit: every composed entry is exact in double (a 90° turn lands on exact zeros,
    // the translations are small integers and halves), so both round to the same floats.
    int covered = 0;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 48; ++x) {
        for (int c = 0; c < 4; ++c) ASSERT_EQ(a.pixel(x, y)[c], b.pixel(x, y)[c]) << x << "," << y;
        covered += a.pixel(x, y)[3] > 0;
      }
    EXPECT_GT(covered, 48 * 32 / 20);  // the objects are in view (not an empty frame twice)
  }
}

TEST(NestedInstances, AGroupHoldingItselfIsRefused) {
  const std::string error = test::sceneErrorOf(std::string(kHeader) + R"(
    "groups": {"a": [{"type": "instance", "group": "b"}],
               "b": [{"type": "instance", "group": "a"}]},
    "objects": [{"type": "instance", "group": "a"}]})");
  EXPECT_NE(error.find("holds an instance of itself"), std::string::npos) << error;
  EXPECT_NE(error.find("groups.b[0]"), std::string::npos) << error;
}

TEST(NestedInstances, AMovingInstanceCannotPlaceNestedGroups) {
  const std::string error = test::sceneErrorOf(std::string(kHeader) + R"(
    "groups": {"leaf": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
               "pair": [{"type": "instance", "group": "leaf"}]},
    "objects": [{"type": "instance", "group": "pair",
                 "motion": {"transform": [{"translate": [0, 0, 0]}, {"translate": [1, 0, 0]}]}}]})");
  EXPECT_NE(error.find("a moving instance cannot place"), std::string::npos) << error;
  EXPECT_NE(error.find("objects[0].motion.transform"), std::string::npos) << error;
}

}  // namespace
}  // namespace glint
