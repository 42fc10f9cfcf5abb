// A function built for baseline x86-64 and for AVX2 (core/avx2_clones.h).
#include "core/avx2_clones.h"

#include <gtest/gtest.h>

namespace glint {
namespace test {
void addOne(float* values, int n);  // avx2_clones_callee.cpp
}  // namespace test
namespace {

// Eight lanes of x² + 1: the AVX2 copy holds them in one register, the baseline copy in two.
using F8 = float __attribute__((vector_size(32)));
GLINT_AVX2_CLONES(void, squaresPlusOne, (const float* x, float* out), (x, out)) {
  F8 v;
  __builtin_memcpy(&v, x, sizeof v);
  v = v * v;
  __builtin_memcpy(out, &v, sizeof v);
  test::addOne(out, 8);
}

TEST(Avx2Clones, LinkAndComputeInTheCopyTheCpuRuns) {
  // Both copies call a function of another file, which Clang 14's LTO dropped under plain
  // target_clones (LLVM issue 58740): the link must succeed and the copy the CPU runs compute.
  // Squares of small integers plus one are exact in float.
  const float x[8] = {0, 1, 2, 3, -4, 5, 6, 7};
  float out[8];
  squaresPlusOne(x, out);
  for (int l = 0; l < 8; ++l) EXPECT_EQ(out[l], x[l] * x[l] + 1) << l;
}

}  // namespace
}  // namespace glint
