// A function built for baseline x86-64 and for AVX2 (core/avx2_clones.h).
#include "core/avx2_clones.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// Eight lanes of x² + 1: the AVX2 copy holds them in one register, the baseline copy in two.
using F8 = float __attribute__((vector_size(32)));
GLINT_AVX2_CLONES(void, squaresPlusOne, (const float* x, float* out), (x, out)) {
  F8 v;
  __builtin_memcpy(&v, x, sizeof v);
  v = v * v + 1.0f;
  __builtin_memcpy(out, &v, sizeof v);
}

TEST(Avx2Clones, LinkAndComputeInTheCopyTheCpuRuns) {
  // Built by target_clones alone, a Clang 14 LTO build failed to link here: its ThinLTO drops
  // the copies (LLVM issue 58740). Squares of small integers plus one are exact in float.
  const float x[8] = {0, 1, 2, 3, -4, 5, 6, 7};
  float out[8];
  squaresPlusOne(x, out);
  for (int l = 0; l < 8; ++l) EXPECT_EQ(out[l], x[l] * x[l] + 1) << l;
}

}  // namespace
}  // namespace glint
