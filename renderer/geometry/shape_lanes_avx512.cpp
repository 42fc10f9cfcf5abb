// intersectLanes' sixteen-lane kernels: this file alone is compiled with -mavx512f.
#include <immintrin.h>

#include "geometry/shape_lanes_isa.h"
#include "geometry/shape_lanes_kernel.h"

namespace glint::shape_lanes {

namespace {
using F32 = float __attribute__((vector_size(64)));
using I32 = int32_t __attribute__((vector_size(64)));
}  // namespace

uint32_t avx512(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits) {
  return sphereBlocks<F32, I32>(s, rays, n, hits, [](F32 v) { return F32(_mm512_sqrt_ps(v)); });
}
uint32_t avx512(const Quad& q, const RayLanes& rays, int n, LaneHits& hits) {
  return quadBlocks<F32, I32>(q, rays, n, hits);
}

}  // namespace glint::shape_lanes
