#include "geometry/shape_lanes.h"

#include <immintrin.h>

#include <algorithm>

#include "core/cpu_features.h"
#include "geometry/shape_lanes_isa.h"
#include "geometry/shape_lanes_kernel.h"

namespace glint {

namespace shape_lanes {

// Baseline x86-64 has SSE2: four lanes everywhere.
namespace {
using F32 = float __attribute__((vector_size(16)));
using I32 = int32_t __attribute__((vector_size(16)));
}  // namespace

uint32_t sse2(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits) {
  return sphereBlocks<F32, I32>(s, rays, n, hits, [](F32 v) { return F32(_mm_sqrt_ps(v)); });
}
uint32_t sse2(const Quad& q, const RayLanes& rays, int n, LaneHits& hits) {
  return quadBlocks<F32, I32>(q, rays, n, hits);
}

}  // namespace shape_lanes

namespace {

float scalarTest(const Sphere& s, const Ray& r, float&, float&) { return intersectSphere(s, r); }
float scalarTest(const Quad& q, const Ray& r, float& u, float& v) {
  return intersectQuad(q, r, u, v);
}

template <class Shape>
uint32_t dispatch(const Shape& shape, const RayLanes& rays, int n, LaneHits& hits, int width) {
  if (width == 0) width = cpuFeatures().avx512f ? 16 : cpuFeatures().avx2 ? 8 : 4;
  // Embree's packet on a machine of its width (the common case): one call.
  if (n == width)
    return width == 16  ? shape_lanes::avx512(shape, rays, n, hits)
           : width == 8 ? shape_lanes::avx2(shape, rays, n, hits)
                        : shape_lanes::sse2(shape, rays, n, hits);
  // Else the widest kernel that fits, then narrower ones, each on the lanes left (through a
  // shifted view, its results moved back into place); a last lane or three one by one.
  uint32_t bits = 0;
  int first = 0;
  const auto run = [&](int w, auto kernel) {
    const int m = (n - first) / w * w;
    if (width < w || m == 0) return;
    RayLanes rest = rays;
    for (int k = 0; k < 3; ++k) rest.o[k] += first, rest.d[k] += first;
    rest.tMin += first;
    rest.tMax += first;
    rest.valid += first;
    LaneHits part;
    bits |= kernel(shape, rest, m, part) << first;
    std::copy_n(part.t, m, hits.t + first);
    std::copy_n(part.u, m, hits.u + first);
    std::copy_n(part.v, m, hits.v + first);
    first += m;
  };
  using Kernel = uint32_t (*)(const Shape&, const RayLanes&, int, LaneHits&);
  run(16, static_cast<Kernel>(shape_lanes::avx512));
  run(8, static_cast<Kernel>(shape_lanes::avx2));
  run(4, static_cast<Kernel>(shape_lanes::sse2));
  for (; first < n; ++first) {
    if (!rays.valid[first]) continue;
    Ray r;
    r.o = {rays.o[0][first], rays.o[1][first], rays.o[2][first]};
    r.d = {rays.d[0][first], rays.d[1][first], rays.d[2][first]};
    r.tMin = rays.tMin[first];
    r.tMax = rays.tMax[first];
    hits.u[first] = hits.v[first] = 0;
    hits.t[first] = scalarTest(shape, r, hits.u[first], hits.v[first]);
    if (hits.t[first] < r.tMax) bits |= 1u << first;
  }
  return bits;
}

}  // namespace

bool laneWidthSupported(int width) {
  return width == 4 || (width == 8 && cpuFeatures().avx2) || (width == 16 && cpuFeatures().avx512f);
}

uint32_t intersectLanes(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits, int width) {
  return dispatch(s, rays, n, hits, width);
}
uint32_t intersectLanes(const Quad& q, const RayLanes& rays, int n, LaneHits& hits, int width) {
  return dispatch(q, rays, n, hits, width);
}

}  // namespace glint
