// Refraction directions (materials/snell.h): Snell's law and total internal reflection.
#include "materials/snell.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Snell, SinesScaleByTheIndexRatio) {
  // n₁ sinθ₁ = n₂ sinθ₂ for a 40° incidence into glass; t stays unit and goes on downwards.
  const float theta = 40.0f * kPi / 180;
  const Vec3f d{std::sin(theta), -std::cos(theta), 0};
  Vec3f t;
  ASSERT_TRUE(refract(d, {0, 1, 0}, 1.0f / 1.5f, t));
  EXPECT_NEAR(1.0f * std::sin(theta), 1.5f * t.x, 1e-6);
  EXPECT_LT(t.y, 0);
  EXPECT_NEAR(length(t), 1, 1e-6);
  // At normal incidence the ray goes straight on.
  ASSERT_TRUE(refract({0, -1, 0}, {0, 1, 0}, 1.0f / 1.5f, t));
  EXPECT_EQ(t, (Vec3f{0, -1, 0}));
}

TEST(Snell, NoRefractedRayPastTheCriticalAngle) {
  // Glass → air: critical angle asin(1/1.5) = 41.81°.
  Vec3f t;
  const float past = 41.9f * kPi / 180, before = 41.7f * kPi / 180;
  EXPECT_FALSE(refract({std::sin(past), -std::cos(past), 0}, {0, 1, 0}, 1.5f, t));
  ASSERT_TRUE(refract({std::sin(before), -std::cos(before), 0}, {0, 1, 0}, 1.5f, t));
  EXPECT_NEAR(t.x, 1.5f * std::sin(before), 1e-6);  // sinθ_t = 1.5 sinθ_i, just below 1
}

}  // namespace
}  // namespace glint
