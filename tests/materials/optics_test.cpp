#include "integrator/optics.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

namespace glint {
namespace {

TEST(Optics, SpecularPowerMatchesPowWithinItsRoundingBound) {
  // Whole exponents go by repeated squaring: each squaring doubles the relative error it is
  // given, so the bound is (2·exponent + 2) float roundings (2^-24 each) of the exact power;
  // below float's smallest normal number (where renders flush to zero) absolutely.
  for (float e : {0.0f, 1.0f, 2.0f, 5.0f, 30.0f, 32.0f, 100.0f, 1000.0f, 65535.0f})
    for (float c = 0; c <= 1; c += 1.0f / 64) {
      const double exact = std::pow(double(c), double(e));
      const double bound =
          (2 * double(e) + 2) * std::ldexp(1.0, -24) * exact + std::numeric_limits<float>::min();
      EXPECT_NEAR(specularPower(c, e), exact, bound) << c << "^" << e;
    }
  EXPECT_EQ(specularPower(0, 0), 1.0f);  // as powf: 0^0 = 1
  EXPECT_EQ(specularPower(1, 65535), 1.0f);
  // Fractional and very large exponents are powf's.
  EXPECT_EQ(specularPower(0.7f, 12.5f), std::pow(0.7f, 12.5f));
  EXPECT_EQ(specularPower(0.999f, 1e6f), std::pow(0.999f, 1e6f));
}

TEST(Optics, FresnelAtNormalIncidence) {
  // R = ((n − 1)/(n + 1))² = (0.5/2.5)² = 0.04 for n = 1.5, from either side.
  EXPECT_NEAR(fresnelDielectric(1, 1, 1.5f), 0.04f, 1e-6);
  EXPECT_NEAR(fresnelDielectric(1, 1.5f, 1), 0.04f, 1e-6);
  EXPECT_NEAR(fresnelSchlick(1, 1, 1.5f), 0.04f, 1e-6);
}

TEST(Optics, FresnelStaysInUnitIntervalForExtremeCosines) {
  for (float c : {0.0f, -0.0f, 1.0f, -1.0f, 1.0f + 1e-7f, 2.0f})
    for (auto [a, b] : {std::pair{1.0f, 1.5f}, std::pair{1.5f, 1.0f}}) {
      const float r = fresnelDielectric(c, a, b);
      EXPECT_GE(r, 0.0f);
      EXPECT_LE(r, 1.0f);
      const float s = fresnelSchlick(c, a, b);
      EXPECT_GE(s, 0.0f);
      EXPECT_LE(s, 1.0f);
    }
  // At grazing incidence (cos 0) everything reflects.
  EXPECT_NEAR(fresnelDielectric(0, 1, 1.5f), 1.0f, 1e-6);
}

TEST(Optics, SnellsLawHolds) {
  // n₁ sinθ₁ = n₂ sinθ₂ to 1e-6 for a 40° incidence into glass.
  const float theta = 40.0f * kPi / 180;
  const Vec3f d{std::sin(theta), -std::cos(theta), 0};
  Vec3f t;
  ASSERT_TRUE(refract(d, {0, 1, 0}, 1.0f / 1.5f, t));
  EXPECT_NEAR(1.0f * std::sin(theta), 1.5f * t.x, 1e-6);
  EXPECT_LT(t.y, 0);
  EXPECT_NEAR(length(t), 1, 1e-6);
}

TEST(Optics, TotalInternalReflectionPastTheCriticalAngle) {
  // Glass → air: critical angle asin(1/1.5) = 41.81°; at 41.9° there is no transmitted ray and
  // Fresnel reflects everything.
  const float theta = 41.9f * kPi / 180;
  const Vec3f d{std::sin(theta), -std::cos(theta), 0};
  Vec3f t;
  EXPECT_FALSE(refract(d, {0, 1, 0}, 1.5f, t));
  EXPECT_EQ(fresnelDielectric(std::cos(theta), 1.5f, 1.0f), 1.0f);
  EXPECT_EQ(fresnelSchlick(std::cos(theta), 1.5f, 1.0f), 1.0f);
  // Just inside the critical angle light still gets out.
  const float inside = 41.7f * kPi / 180;
  EXPECT_TRUE(refract({std::sin(inside), -std::cos(inside), 0}, {0, 1, 0}, 1.5f, t));
}

TEST(Optics, BeerNeverProducesNaN) {
  EXPECT_NEAR(beerChannel(0.5f, 2), 0.25f, 1e-7);  // 0.5² per two units
  EXPECT_EQ(beerChannel(1, kInfinity), 1.0f);      // clear medium, infinite path: ln 1·∞ avoided
  EXPECT_EQ(beerChannel(0.5f, kInfinity), 0.0f);
  EXPECT_EQ(beerChannel(0, 0.001f), 0.0f);  // ln 0 = −∞ avoided
  EXPECT_EQ(beerChannel(0, 0), 1.0f);       // no distance, no absorption
}

// The integrator takes a medium's logarithms once (BeerMedium); that must change no bit of what
// beer() gives, at the edges (a of 0 or 1, no distance, infinite distance) and in between.
TEST(Optics, BeerMediumGivesBeerBitForBit) {
  const float as[] = {0, 1e-30f, 0.01f, 0.5f, 0.92f, 0.999999f, 1};
  const float ss[] = {0, 1e-6f, 0.37f, 1, 12.5f, 1e4f, kInfinity};
  int compared = 0;
  for (const float r : as)
    for (const float g : as) {
      const Rgb a{r, g, 0.5f};
      const BeerMedium medium(a);
      for (const float s : ss) {
        const Rgb once = medium.transmittance(s), each = beer(a, s);
        EXPECT_TRUE(std::memcmp(&once, &each, sizeof(Rgb)) == 0)
            << "a (" << r << ", " << g << ") s " << s << ": " << once.r << " " << once.g
            << " against " << each.r << " " << each.g;
        ++compared;
      }
    }
  EXPECT_EQ(compared, 7 * 7 * 7);
}

}  // namespace
}  // namespace glint
