// The refracting interface (materials/dielectric.h) on its own: where light meeting it goes,
// and how much, against Fresnel and Snell.
#include "materials/dielectric.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

Vec3f down(float degrees) {  // unit, travelling downwards at `degrees` from the −y axis
  const float a = degrees * kPi / 180;
  return {std::sin(a), -std::cos(a), 0};
}

TEST(Dielectric, SplitsIntoReflectionAndRefractionAtNormalIncidence) {
  const Dielectric glass;  // ior 1.5, exact Fresnel
  const Dielectric::Split s = glass.split({0, -1, 0}, {0, 1, 0}, 1, 1.5f);
  EXPECT_NEAR(s.R, 0.04f, 1e-7);  // ((1.5 − 1)/(1.5 + 1))²: reflected; 0.96 refracted
  EXPECT_EQ(s.reflected, (Vec3f{0, 1, 0}));
  ASSERT_TRUE(s.refracts);
  EXPECT_EQ(s.refracted, (Vec3f{0, -1, 0}));  // straight on
}

TEST(Dielectric, ReflectsAtTheIncidentAngleAndRefractsBySnell) {
  const Dielectric glass;
  const Dielectric::Split s = glass.split(down(40), {0, 1, 0}, 1, 1.5f);
  // The mirror direction: the same angle on the other side of the normal, going up.
  EXPECT_NEAR(s.reflected.x, std::sin(40 * kPi / 180), 1e-6);
  EXPECT_NEAR(s.reflected.y, std::cos(40 * kPi / 180), 1e-6);
  ASSERT_TRUE(s.refracts);
  EXPECT_NEAR(1.5f * s.refracted.x, std::sin(40 * kPi / 180), 1e-6);  // n₁ sinθ₁ = n₂ sinθ₂
  // The Fresnel equations at 40° in double: r_s = −0.277773, r_p = 0.119623, R = 0.0457336.
  EXPECT_NEAR(s.R, 0.0457336, 1e-6);
}

TEST(Dielectric, TotalInternalReflectionSendsEverythingBack) {
  // From glass into air at 45°, past the critical angle asin(1/1.5) = 41.81°.
  const Dielectric glass;
  const Dielectric::Split s = glass.split(down(45), {0, 1, 0}, 1.5f, 1);
  EXPECT_EQ(s.R, 1.0f);
  EXPECT_FALSE(s.refracts);
  // At 41.7° some light still leaves.
  const Dielectric::Split before = glass.split(down(41.7f), {0, 1, 0}, 1.5f, 1);
  EXPECT_LT(before.R, 1.0f);
  EXPECT_TRUE(before.refracts);
}

TEST(Dielectric, SchlickWhenAskedFor) {
  Dielectric glass;
  glass.fresnel = FresnelModel::Schlick;
  // 0.04 + 0.96·(1 − cos 60°)⁵ = 0.07.
  EXPECT_NEAR(glass.split(down(60), {0, 1, 0}, 1, 1.5f).R, 0.07f, 1e-6);
}

}  // namespace
}  // namespace glint
