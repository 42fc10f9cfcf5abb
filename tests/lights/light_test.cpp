// Light sources (lights/light.h) on their own: what one sample delivers at a point, against the
// closed forms of seed 000 §4.5 and §13.4.2, and the radiance a visible area light shows.
#include "lights/light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

TEST(Lights, PointLightFallsOffOnlyWhenAsked) {
  // A light at (1, 2, 0) seen from the origin: r² = 5, direction (1, 2, 0)/√5.
  const PointLight plain{{1, 2, 0}, {3, 3, 3}, Falloff::None};
  const LightSample s = sampleLight(plain, {0, 0, 0}, {0, 0, 1}, {});
  EXPECT_NEAR(s.wi.x, 1 / std::sqrt(5.0f), 1e-7);
  EXPECT_NEAR(s.wi.y, 2 / std::sqrt(5.0f), 1e-7);
  EXPECT_EQ(s.target, (Vec3f{1, 2, 0}));
  EXPECT_FALSE(s.atInfinity);
  EXPECT_EQ(s.intensity, (Rgb{3, 3, 3}));
  const PointLight falling{{1, 2, 0}, {3, 3, 3}, Falloff::InverseSquare};
  EXPECT_NEAR(sampleLight(falling, {0, 0, 0}, {0, 0, 1}, {}).intensity.r, 3.0f / 5, 1e-7);
}

TEST(Lights, SpotLightShinesFullyInsideItsInnerConeAndFadesToItsOuter) {
  // Down the −y axis from (0, 1, 0), inner 20°, outer 40°: glTF's fade, the square of the
  // cosine's linear ramp between the two cones.
  PointLight spot{{0, 1, 0}, {2, 2, 2}, Falloff::None};
  spot.spotAxis = {0, -1, 0};
  spot.cosInner = std::cos(20 * kPi / 180);
  spot.cosOuter = std::cos(40 * kPi / 180);
  ASSERT_TRUE(spot.isSpot());
  const auto at = [&](float degrees) {  // a point on the unit sphere `degrees` off the axis
    const float a = degrees * kPi / 180;
    return sampleLight(spot, Vec3f{std::sin(a), 1 - std::cos(a), 0}, {0, 0, 1}, {}).intensity.r;
  };
  EXPECT_FLOAT_EQ(at(0), 2);   // on the axis
  EXPECT_FLOAT_EQ(at(19), 2);  // inside the inner cone
  // 30°: t = (cos 30° − cos 40°)/(cos 20° − cos 40°) = 0.099981/0.173649 = 0.575766, t² = 0.331507.
  EXPECT_NEAR(at(30), 2 * 0.331507f, 1e-5);
  EXPECT_EQ(at(41), 0);   // outside the outer cone
  EXPECT_EQ(at(120), 0);  // behind the light
  // A plain point light has no axis and no cone.
  EXPECT_FALSE((PointLight{{0, 1, 0}, {2, 2, 2}, Falloff::None}.isSpot()));
}

TEST(Lights, DirectionalLightIsAtInfinity) {
  const DirectionalLight sun{{0, -1, 0}, {0.5f, 0.5f, 0.5f}};
  const LightSample s = sampleLight(sun, {7, 3, -2}, {0, 0, 1}, {});
  EXPECT_TRUE(s.atInfinity);
  EXPECT_EQ(s.wi, (Vec3f{0, 1, 0}));  // towards the light: against its travel
  EXPECT_EQ(s.intensity, (Rgb{0.5f, 0.5f, 0.5f}));
}

TEST(Lights, QuadInRadianceModeCarriesItsGeometryTerm) {
  // A 2 × 2 quad facing down at height 2, radiance L = 3; from the origin, the sample at its
  // centre: cosθ_y = 1, r = 2, so L·cos·A/r² = 3·1·4/4 = 3.
  QuadLight q({-1, 2, -1}, {2, 0, 0}, {0, 0, 2});
  q.intensity = {3, 3, 3};
  q.emission = Emission::Radiance;
  EXPECT_EQ(q.normal(), (Vec3f{0, -1, 0}));
  EXPECT_EQ(q.area(), 4.0f);
  const LightSample centre = sampleLight(Light{q}, {0, 0, 0}, {0, 0, 1}, {0.5f, 0.5f});
  EXPECT_EQ(centre.target, (Vec3f{0, 2, 0}));
  EXPECT_NEAR(centre.intensity.r, 3.0f, 1e-6);
  // Behind the emitting side nothing arrives.
  EXPECT_TRUE(sampleLight(Light{q}, {0, 4, 0}, {0, 0, 1}, {0.5f, 0.5f}).intensity.isBlack());
  // In seed mode a sample is a point light of the light's intensity.
  q.emission = Emission::Seed;
  EXPECT_EQ(sampleLight(Light{q}, {0, 4, 0}, {0, 0, 1}, {0.25f, 0.75f}).intensity, (Rgb{3, 3, 3}));
}

TEST(Lights, DiskSamplesLieOnTheDisk) {
  const Vec3f normal = normalize(Vec3f{1, 2, -0.5f});
  const DiskLight d({1, 5, 2}, normal, 0.75f);
  for (float ux = 0; ux < 1; ux += 1.0f / 7)
    for (float uy = 0; uy < 1; uy += 1.0f / 7) {
      const Vec3f y = sampleLight(Light{d}, {0, 0, 0}, {0, 0, 1}, {ux, uy}).target - d.center();
      EXPECT_NEAR(dot(y, normal), 0, 1e-6);       // in the disk's plane
      EXPECT_LE(length(y), 0.75f * (1 + 1e-6f));  // within its radius
    }
}

TEST(Lights, VisibleRadianceInBothModes) {
  // Radiance mode shows the intensity; seed mode intensity / area (docs/effects.md).
  AreaEmission e;
  e.intensity = {2, 4, 6};
  e.emission = Emission::Radiance;
  EXPECT_EQ(e.emittedRadiance(8), (Rgb{2, 4, 6}));
  e.emission = Emission::Seed;
  EXPECT_EQ(e.emittedRadiance(8), (Rgb{0.25f, 0.5f, 0.75f}));
}

TEST(Lights, AnAreaLightIsTheMeanOfItsSamples) {
  EXPECT_EQ(meanOverSamples({4, 8, 12}, 4), (Rgb{1, 2, 3}));
  EXPECT_EQ(meanOverSamples({0.3f, 0.3f, 0.3f}, 1), (Rgb{0.3f, 0.3f, 0.3f}));  // exactly
  QuadLight q({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  q.samples = 9;
  EXPECT_EQ(lightSampleCount(Light{q}), 9);
  EXPECT_EQ(lightSampleCount(Light{PointLight{}}), 1);
}

TEST(Lights, AQuadLightOfAnySizeHasItsAreaAndAUnitNormal) {
  // Edges of 10^10: |edge1 × edge2| = 10^20 squares past float's range, and the light's area
  // was +∞ and its normal (0, 0, 0), a dark light.
  const QuadLight huge({0, 0, 0}, {1e10f, 0, 0}, {0, 1e10f, 0});
  EXPECT_FLOAT_EQ(huge.area(), 1e20f);
  EXPECT_FLOAT_EQ(huge.normal().z, 1);
  const QuadLight unit({0, 0, 0}, {2, 0, 0}, {0, 3, 0});
  EXPECT_EQ(unit.area(), 6);
  EXPECT_EQ(unit.normal().z, 1);
}

}  // namespace
}  // namespace glint
