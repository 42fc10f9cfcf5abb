#include "geometry/sphere_lanes.h"

#include <immintrin.h>

#include "geometry/sphere_lanes_isa.h"
#include "geometry/sphere_lanes_kernel.h"

namespace glint {

namespace sphere_lanes {

// Baseline x86-64 has SSE2: four lanes everywhere.
uint32_t sse2(const Sphere& s, const RayLanes& rays, int n, float* tHit) {
  using F32 = float __attribute__((vector_size(16)));
  using I32 = int32_t __attribute__((vector_size(16)));
  uint32_t hits = 0;
  for (int first = 0; first < n; first += 4)
    hits |= sphereLanes<F32, I32>(s, rays, first, tHit, [](F32 v) { return F32(_mm_sqrt_ps(v)); });
  return hits;
}

}  // namespace sphere_lanes

namespace {

// __builtin_cpu_init first: this may run among static constructors, before libgcc's own.
const bool kHaveAvx2 = (__builtin_cpu_init(), __builtin_cpu_supports("avx2"));
const bool kHaveAvx512 = (__builtin_cpu_init(), __builtin_cpu_supports("avx512f"));

}  // namespace

bool sphereLaneWidthSupported(int width) {
  return width == 4 || (width == 8 && kHaveAvx2) || (width == 16 && kHaveAvx512);
}

uint32_t intersectSphereLanes(const Sphere& s, const RayLanes& rays, int n, float* tHit,
                              int width) {
  if (width == 0) width = kHaveAvx512 ? 16 : kHaveAvx2 ? 8 : 4;
  // Embree's packet on a machine of its width (the common case): one call.
  if (n == width)
    return width == 16  ? sphere_lanes::avx512(s, rays, n, tHit)
           : width == 8 ? sphere_lanes::avx2(s, rays, n, tHit)
                        : sphere_lanes::sse2(s, rays, n, tHit);
  // Else the widest kernel that fits, then narrower ones; a last lane or three one by one.
  uint32_t hits = 0;
  int first = 0;
  const auto run = [&](int w, auto kernel) {
    const int m = (n - first) / w * w;
    if (width < w || m == 0) return;
    RayLanes rest = rays;
    for (int k = 0; k < 3; ++k) rest.o[k] += first, rest.d[k] += first;
    rest.tMin += first;
    rest.tMax += first;
    rest.valid += first;
    hits |= kernel(s, rest, m, tHit + first) << first;
    first += m;
  };
  run(16, sphere_lanes::avx512);
  run(8, sphere_lanes::avx2);
  run(4, sphere_lanes::sse2);
  for (; first < n; ++first) {
    if (!rays.valid[first]) continue;
    Ray r;
    r.o = {rays.o[0][first], rays.o[1][first], rays.o[2][first]};
    r.d = {rays.d[0][first], rays.d[1][first], rays.d[2][first]};
    r.tMin = rays.tMin[first];
    r.tMax = rays.tMax[first];
    tHit[first] = intersectSphere(s, r);
    if (tHit[first] < r.tMax) hits |= 1u << first;
  }
  return hits;
}

}  // namespace glint
