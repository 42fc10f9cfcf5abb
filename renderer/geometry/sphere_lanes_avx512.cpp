// intersectSphereLanes' sixteen-lane kernel: this file alone is compiled with -mavx512f.
#include <immintrin.h>

#include "geometry/sphere_lanes_isa.h"
#include "geometry/sphere_lanes_kernel.h"

namespace glint::sphere_lanes {

uint32_t avx512(const Sphere& s, const RayLanes& rays, int n, float* tHit) {
  using F32 = float __attribute__((vector_size(64)));
  using I32 = int32_t __attribute__((vector_size(64)));
  uint32_t hits = 0;
  for (int first = 0; first < n; first += 16)
    hits |=
        sphereLanes<F32, I32>(s, rays, first, tHit, [](F32 v) { return F32(_mm512_sqrt_ps(v)); });
  return hits;
}

}  // namespace glint::sphere_lanes
