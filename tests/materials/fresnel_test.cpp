// Fresnel reflectance (materials/fresnel.h) against its closed forms at normal incidence, 45°,
// the critical angle and grazing incidence.
#include "materials/fresnel.h"

#include <gtest/gtest.h>

#include <utility>

#include "core/vec.h"

namespace glint {
namespace {

TEST(Fresnel, AtNormalIncidence) {
  // R = ((n − 1)/(n + 1))² = (0.5/2.5)² = 0.04 for n = 1.5, from either side; Schlick's R₀ is
  // the same number.
  EXPECT_NEAR(fresnelDielectric(1, 1, 1.5f), 0.04f, 1e-7);
  EXPECT_NEAR(fresnelDielectric(1, 1.5f, 1), 0.04f, 1e-7);
  EXPECT_NEAR(fresnelSchlick(1, 1, 1.5f), 0.04f, 1e-7);
  EXPECT_NEAR(fresnelSchlick(1, 1.5f, 1), 0.04f, 1e-7);
  // Matched indices reflect nothing, up to the square of a float rounding of cosθ_t.
  EXPECT_NEAR(fresnelDielectric(0.3f, 1.33f, 1.33f), 0.0f, 1e-12);
}

TEST(Fresnel, AtFortyFiveDegreesIntoGlass) {
  // cosθ_i = cos 45°, sinθ_t = sin 45°/1.5: r_s = −0.303337, r_p = 0.092013 (the Fresnel
  // equations in double), R = (r_s² + r_p²)/2 = 0.0502399; float rounding stays below 1e-6.
  const float c = std::cos(kPi / 4);
  EXPECT_NEAR(fresnelDielectric(c, 1, 1.5f), 0.0502399, 1e-6);
  // Schlick: 0.04 + 0.96·(1 − cos 45°)⁵ = 0.0420693.
  EXPECT_NEAR(fresnelSchlick(c, 1, 1.5f), 0.0420693, 1e-6);
}

TEST(Fresnel, EverythingReflectsPastTheCriticalAngleAndAtGrazing) {
  // Glass → air: critical angle asin(1/1.5) = 41.81°; at 41.9° total internal reflection.
  const float past = std::cos(41.9f * kPi / 180), before = std::cos(41.7f * kPi / 180);
  EXPECT_EQ(fresnelDielectric(past, 1.5f, 1), 1.0f);
  EXPECT_EQ(fresnelSchlick(past, 1.5f, 1), 1.0f);
  EXPECT_LT(fresnelDielectric(before, 1.5f, 1), 1.0f);
  // At grazing incidence (cos 0) everything reflects, from either side.
  EXPECT_NEAR(fresnelDielectric(0, 1, 1.5f), 1.0f, 1e-6);
  EXPECT_NEAR(fresnelSchlick(0, 1, 1.5f), 1.0f, 1e-6);
}

TEST(Fresnel, StaysInTheUnitIntervalForExtremeCosines) {
  for (float c : {0.0f, -0.0f, 1.0f, -1.0f, 1.0f + 1e-7f, 2.0f, kInfinity})
    for (auto [a, b] : {std::pair{1.0f, 1.5f}, std::pair{1.5f, 1.0f}})
      for (FresnelModel m : {FresnelModel::Exact, FresnelModel::Schlick}) {
        const float r = fresnel(m, c, a, b);
        EXPECT_GE(r, 0.0f) << c;
        EXPECT_LE(r, 1.0f) << c;
      }
}

}  // namespace
}  // namespace glint
