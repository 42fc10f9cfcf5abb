// Rays Embree would assert on (core/ray.h) never reach it: toRtcRay turns them into an empty
// segment, and the range shrinks by what an instance's inverse transform grows a coordinate.
#include <gtest/gtest.h>

#include <limits>

#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "core/error.h"
#include "test_util.h"

namespace glint {
namespace {

TEST(EmbreeRange, RaysPastEmbreesRangeMissInsteadOfAborting) {
  const Scene scene = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "box", "min": [-1,-1,-1], "max": [1,1,1], "material": "m"}]})");
  const EmbreeAccel embree(scene);
  // The camera at the origin: render space is world space. No instances: the range is
  // Embree's 1.844e18 less 1 % for rounding.
  EXPECT_FLOAT_EQ(embree.rayRange().origin, 0.99f * kEmbreeMaxRayCoordinate);
  // From z = 5 straight down -z, the box's face at z = 1: t = 4.
  Ray ray{{0, 0, 5}, {0, 0, -1}};
  EXPECT_NEAR(embree.intersect(ray).t, 4.0f, 1e-5f);
  // A direction of 1e19 (once `validate --ray "0 0 5 0 0 -1e19 0 inf 0"`, SIGABRT): no hit,
  // nothing blocked; so for a NaN tmax and a time past 1.
  for (Ray bad : {Ray{{0, 0, 5}, {0, 0, -1e19f}},
                  Ray{{0, 0, 5}, {0, 0, -1}, 0, std::numeric_limits<float>::quiet_NaN()},
                  Ray{{0, 0, 5}, {0, 0, -1}, 0, kInfinity, 2}}) {
    EXPECT_FALSE(embree.intersect(bad)) << formatRay(bad);
    EXPECT_FALSE(embree.occluded(bad)) << formatRay(bad);
  }
  EXPECT_NE(rayProblem(Ray{{0, 0, 5}, {0, 0, -1e19f}}), "");
}

TEST(EmbreeRange, AnInstanceThatShrinksItsGroupShrinksTheRange) {
  // Scaled by 1e-6, the inverse grows coordinates 1e6 times: origins up to 0.99·1.844e18/1e6 =
  // 1.8256e12 stay valid in the instance's space, and the instance is still hit: from z = 5 the
  // scaled box's face at z = 1e-6, t = 5 − 1e-6.
  const Scene scene = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "instance", "group": "g", "transform": {"scale": [1e-6, 1e-6, 1e-6]}}],
    "groups": {"g": [{"type": "box", "min": [-1,-1,-1], "max": [1,1,1], "material": "m"}]}})");
  const EmbreeAccel embree(scene);
  EXPECT_NEAR(embree.rayRange().origin, 0.99 * 1.844e18 / 1e6, 1e7);
  EXPECT_NEAR(embree.intersect(Ray{{0, 0, 5}, {0, 0, -1}}).t, 5.0f, 1e-5f);
  EXPECT_FALSE(embree.intersect(Ray{{0, 0, 1e13f}, {0, 0, -1}}));
}

TEST(EmbreeRange, InstancesShrinkingTheRangeBelowTheSceneAreRefused) {
  // Scaled by 1e-12, the inverse grows coordinates 1e12 times: Embree then takes rays only from
  // within 0.99 · 1.844e18 / 1e12 ≈ 1.83e6 of the origin, but a sphere at x = 1e7 starts rays
  // from there. Dropping them would be a silent wrong image: the accelerator refuses the scene.
  const Scene scene = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "instance", "group": "g", "transform": {"scale": [1e-12, 1e-12, 1e-12]}},
                {"type": "sphere", "center": [1e7, 0, 0], "radius": 1, "material": "m"}],
    "groups": {"g": [{"type": "box", "min": [-1,-1,-1], "max": [1,1,1], "material": "m"}]}})");
  try {
    const EmbreeAccel embree(scene);
    ADD_FAILURE() << "built";
  } catch (const UsageError& e) {
    // The instance is named, as objects[0] (it has no name).
    EXPECT_NE(std::string(e.what()).find("the scene reaches 1e+07 from the camera, but the "
                                         "transform of objects[0] shrinks so much"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace glint
