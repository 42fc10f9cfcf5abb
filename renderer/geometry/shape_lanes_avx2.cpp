// intersectLanes' eight-lane kernels, built for AVX2 alone (core/target_region.h).
#include <immintrin.h>

#include <cstring>
#include <limits>

#include "core/target_region.h"
#include "geometry/shape_lanes.h"
#include "geometry/shape_lanes_isa.h"

GLINT_TARGET_REGION_BEGIN("avx2")
#include "geometry/shape_lanes_kernel.h"

namespace glint::shape_lanes {

namespace {
using F32 = float __attribute__((vector_size(32)));
using I32 = int32_t __attribute__((vector_size(32)));
// A struct, not a lambda, whose conversion to a function pointer would be built for baseline
// x86-64 (and warned of).
struct Sqrt {
  F32 operator()(F32 v) const { return F32(_mm256_sqrt_ps(v)); }
};
}  // namespace

uint32_t avx2(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits) {
  return sphereBlocks<F32, I32>(s, rays, n, hits, Sqrt{});
}
uint32_t avx2(const Quad& q, const RayLanes& rays, int n, LaneHits& hits) {
  return quadBlocks<F32, I32>(q, rays, n, hits);
}

}  // namespace glint::shape_lanes
GLINT_TARGET_REGION_END
