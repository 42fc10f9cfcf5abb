#include "core/sin_cos.h"

#include <cmath>

namespace glint {

namespace sin_cos {
void inLanes(const float* x, int n, float* s, float* c);  // sin_cos_fma.cpp
}  // namespace sin_cos

namespace {

// Glibc's own test for taking its FMA build. __builtin_cpu_init first: this may run among
// static constructors, before libgcc's own.
const bool kLanes =
    (__builtin_cpu_init(), __builtin_cpu_supports("fma") && __builtin_cpu_supports("avx2"));

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
