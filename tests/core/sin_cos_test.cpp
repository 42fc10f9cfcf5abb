#include "core/sin_cos.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace glint {
namespace {

bool sameBits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

// sinCos stands in for std::sin and std::cos where the environment light draws its
// directions, and an image must not change by a bit: every lane must give the C library's
// float. The arguments cover glibc's branches and their edges (below 2^-12, below π/4, the
// reduction up to 120, beyond it, infinities and NaN) and, between them, every 4096th float
// up to 128 of either sign, in an odd count so that the last ones take the one-at-a-time path.
TEST(SinCos, MatchesTheCLibraryBitForBit) {
  if (!sinCosInLanes())
    GTEST_SKIP() << "sinCos calls the C library itself here (no FMA and AVX2, or a C library whose "
                    "floats its lanes do not give)";
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> x = {0.0f,
                          -0.0f,
                          0x1p-149f,
                          0x1p-126f,
                          0x1.fffffep-13f,
                          0x1p-12f,
                          0.75f,
                          0x1.921fb4p-1f,
                          0x1.921fb6p-1f,
                          0x1.921fb6p+0f,
                          0x1.921fb6p+1f,
                          0x1.dffffep+6f,
                          120.0f,
                          1e6f,
                          kInf,
                          -kInf,
                          std::numeric_limits<float>::quiet_NaN()};
  for (uint32_t bits = 0; bits <= std::bit_cast<uint32_t>(128.0f); bits += 4096) {
    x.push_back(std::bit_cast<float>(bits));
    x.push_back(-std::bit_cast<float>(bits));
  }
  if (x.size() % 4 == 0) x.push_back(2.5f);
  std::vector<float> s(x.size()), c(x.size());
  sinCos(x.data(), static_cast<int>(x.size()), s.data(), c.data());
  int wrong = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const float expectedSin = std::sin(x[i]), expectedCos = std::cos(x[i]);
    if (!sameBits(s[i], expectedSin) || !sameBits(c[i], expectedCos)) {
      if (++wrong <= 5)
        ADD_FAILURE() << "x = " << std::hexfloat << x[i] << ": sin " << s[i] << " (C library "
                      << expectedSin << "), cos " << c[i] << " (" << expectedCos << ")";
    }
  }
  EXPECT_EQ(wrong, 0) << "of " << x.size();
}

}  // namespace
}  // namespace glint
