#include "core/sin_cos.h"

#include <cmath>

#include "core/cpu_features.h"

namespace glint {

namespace sin_cos {
void inLanes(const float* x, int n, float* s, float* c);  // sin_cos_fma.cpp
}  // namespace sin_cos

namespace {

// Whether the lanes give this process's C library's floats: its FMA build runs where the CPU
// has FMA and AVX2, and a C library other than glibc's 2.28 or later, or a build of it made
// otherwise, would answer differently; probe arguments in every quadrant, near the cut-offs
// and at a tiny and a negative one are compared before the lanes are trusted.
bool lanesMatchTheCLibrary() {
  if (!cpuFeatures().fma || !cpuFeatures().avx2) return false;
  constexpr int kProbes = 16;
  const float x[kProbes] = {0.1f,  0.7853f, 1.0f,  2.0f,  3.0f,   4.0f,  5.5f,   -1.3f,
                            -6.0f, 10.0f,   33.3f, 100.f, 119.9f, 1e-5f, -77.7f, 0.5f};
  float s[kProbes], c[kProbes];
  sin_cos::inLanes(x, kProbes, s, c);
  for (int i = 0; i < kProbes; ++i)
    if (s[i] != std::sin(x[i]) || c[i] != std::cos(x[i])) return false;
  return true;
}

const bool kLanes = lanesMatchTheCLibrary();

}  // namespace

bool sinCosInLanes() { return kLanes; }

void sinCos(const float* x, int n, float* s, float* c) {
  if (kLanes) return sin_cos::inLanes(x, n, s, c);
  for (int i = 0; i < n; ++i) {
    s[i] = std::sin(x[i]);
    c[i] = std::cos(x[i]);
  }
}

}  // namespace glint
