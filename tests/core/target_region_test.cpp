// Functions built for an instruction set by a target region (core/target_region.h).
#include "core/target_region.h"

#include <gtest/gtest.h>
#include <immintrin.h>

#include <algorithm>

#include "core/cpu_features.h"

namespace glint {
namespace {

// Declared before the region: built for baseline x86-64 (the region's own code may call it).
float half(float x) { return 0.5f * x; }

GLINT_TARGET_REGION_BEGIN("avx2")
// Eight floats in one AVX2 register: its intrinsics compile only in a function built for AVX2.
// Returns half their sum, through the baseline function, and the lanes' maximum of x + y as
// AVX2's integer lanes give it.
float halfSumInAvx2(const float* x) {
  const __m256 v = _mm256_loadu_ps(x);
  const __m128 pairs = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  float lanes[4];
  _mm_storeu_ps(lanes, pairs);
  return half((lanes[0] + lanes[1]) + (lanes[2] + lanes[3]));
}
int maxOfSumsInAvx2(const int* x, const int* y) {
  const __m256i s = _mm256_add_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(x)),
                                     _mm256_loadu_si256(reinterpret_cast<const __m256i*>(y)));
  int lanes[8];
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(lanes), s);
  int most = lanes[0];
  for (int l = 1; l < 8; ++l) most = std::max(most, lanes[l]);
  return most;
}
GLINT_TARGET_REGION_END

TEST(TargetRegion, BuildsItsFunctionsForTheInstructionSet) {
  if (!cpuFeatures().avx2) GTEST_SKIP() << "no AVX2 on this CPU";
  // 1 + 2 + … + 8 = 36, exact in float: half is 18.
  const float x[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_EQ(halfSumInAvx2(x), 18.0f);
  // (7 + 10) is the largest lane sum; AVX2's 256-bit integer add (VPADDD ymm) gives it.
  const int a[8] = {1, 2, 3, 4, 5, 6, 7, 0}, b[8] = {1, 1, 1, 1, 1, 1, 10, 2};
  EXPECT_EQ(maxOfSumsInAvx2(a, b), 17);
}

}  // namespace
}  // namespace glint
