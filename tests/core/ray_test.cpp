#include "core/ray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/hash.h"

namespace glint {
namespace {

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

// nextFloatUp/Down replace std::nextafter(x, ±∞) in the ray offset (a libm call on x86-64):
// they must give the same float for every input class, bit for bit.
TEST(Ray, NextFloatMatchesNextafter) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> values = {0.0f,
                               -0.0f,
                               std::numeric_limits<float>::denorm_min(),
                               -std::numeric_limits<float>::denorm_min(),
                               std::numeric_limits<float>::min(),
                               -std::numeric_limits<float>::min(),
                               std::numeric_limits<float>::max(),
                               -std::numeric_limits<float>::max(),
                               kInf,
                               -kInf,
                               1.0f,
                               -1.0f,
                               0x1p-126f,
                               -0x1p-126f,
                               3.5e-39f,
                               -3.5e-39f};
  for (int i = 0; i < 2000; ++i) {  // random bit patterns: every exponent, both signs
    const auto bits = static_cast<uint32_t>(hashKey(11, static_cast<uint32_t>(i)));
    const float x = std::bit_cast<float>(bits);
    if (!std::isnan(x)) values.push_back(x);
  }
  for (const float x : values) {
    EXPECT_TRUE(sameBits(nextFloatUp(x), std::nextafter(x, kInf))) << x;
    EXPECT_TRUE(sameBits(nextFloatDown(x), std::nextafter(x, -kInf))) << x;
  }
  EXPECT_TRUE(std::isnan(nextFloatUp(std::numeric_limits<float>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(nextFloatDown(std::numeric_limits<float>::quiet_NaN())));
}

}  // namespace
}  // namespace glint
