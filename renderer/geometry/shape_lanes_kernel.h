#pragma once
// The lane kernels behind intersectLanes, written once over GNU vector types and compiled three
// times, each in its own file with its own instruction set (shape_lanes*.cpp; the AVX ones
// include this inside their target region, core/target_region.h, after every other header): the
// anonymous namespace gives each file its own copy, so the linker cannot swap an AVX-512 copy
// into the SSE2 build. Include only from those files.
#include <cstring>
#include <limits>

#include "geometry/shape_lanes.h"

namespace glint {
// std::bit_cast, built for the including file's instruction set: unoptimised it is a call, and
// std::bit_cast's copy is built for baseline x86-64, which takes an AVX kernel's vectors wrongly.
// Not in the anonymous namespace, where GCC inlined it otherwise and the kernels' code changed;
// each file instantiates it for vectors of its own width only, so no copy can stand in for
// another file's.
template <class To, class From>
constexpr To bitsAs(const From& x) noexcept {
  // A scalar instantiation would be one COMDAT shared by files of different instruction sets.
  static_assert(sizeof(To) == sizeof(From) && sizeof(From) >= 16, "bitsAs casts lanes only");
  return __builtin_bit_cast(To, x);
}

namespace {

// Lanes [first, first + W) of a packet, W the lanes of F32 (I32: as many int32_t), with the
// operations the kernels share. Ignored lanes hold a harmless ray (origin 0, direction
// (1, 1, 1)), so that whatever Embree left in them cannot raise a floating-point exception.
template <class F32, class I32>
struct Lanes {
  static constexpr int W = sizeof(F32) / sizeof(float);
  F32 o[3], d[3], tMin, tMax;
  I32 valid;

  [[gnu::always_inline]] Lanes(const RayLanes& rays, int first) {
    I32 flags;
    std::memcpy(&flags, rays.valid + first, sizeof flags);
    valid = flags != 0;
    const F32 zero = splat(0), one = splat(1);
    for (int k = 0; k < 3; ++k) {
      o[k] = select(valid, load(rays.o[k], first), zero);
      d[k] = select(valid, load(rays.d[k], first), one);
    }
    tMin = load(rays.tMin, first);
    tMax = load(rays.tMax, first);
  }
  [[gnu::always_inline]] static F32 load(const float* p, int first) {
    F32 v;
    std::memcpy(&v, p + first, sizeof v);
    return v;
  }
  [[gnu::always_inline]] static F32 splat(float x) { return F32{} + x; }
  [[gnu::always_inline]] static F32 select(I32 mask, F32 a, F32 b) {
    return bitsAs<F32>((mask & bitsAs<I32>(a)) | (~mask & bitsAs<I32>(b)));
  }
  // Lane l's t, u, v into hits at first + l; its bit (first + l) where `hit`.
  [[gnu::always_inline]] static uint32_t store(I32 hit, F32 t, F32 u, F32 v, int first,
                                               LaneHits& hits) {
    std::memcpy(hits.t + first, &t, sizeof t);
    std::memcpy(hits.u + first, &u, sizeof u);
    std::memcpy(hits.v + first, &v, sizeof v);
    uint32_t bits = 0;
    for (int l = 0; l < W; ++l) bits |= hit[l] ? 1u << (first + l) : 0u;
    return bits;
  }
};

// intersectSphere (shapes.cpp) line by line, branches turned into selects. `sqrtLanes` is the
// file's square root of F32 (GNU vectors have none).
template <class F32, class I32, class Sqrt>
[[gnu::always_inline]] inline uint32_t sphereLanes(const Sphere& s, const RayLanes& rays, int first,
                                                   LaneHits& hits, Sqrt sqrtLanes) {
  using L = Lanes<F32, I32>;
  const L r(rays, first);
  const F32 zero = L::splat(0);
  const F32 fx = r.o[0] - s.center.x, fy = r.o[1] - s.center.y, fz = r.o[2] - s.center.z;
  const F32 &dx = r.d[0], &dy = r.d[1], &dz = r.d[2];
  const F32 a = dx * dx + dy * dy + dz * dz;
  const F32 b = -(fx * dx + fy * dy + fz * dz);
  const F32 ba = b / a;
  const F32 lx = fx + dx * ba, ly = fy + dy * ba, lz = fz + dz * ba;
  const float r2 = s.radius * s.radius;
  const F32 disc = a * (r2 - (lx * lx + ly * ly + lz * lz));
  const I32 missed = disc < 0;
  const F32 c = (fx * fx + fy * fy + fz * fz) - r2;
  // std::copysign(root, b): the root's magnitude bits with b's sign bit. A missed lane's root
  // is of 0, not of a negative number (no invalid-operation flag); its result is discarded.
  const I32 signBit = I32{} + std::numeric_limits<int32_t>::min();
  const F32 root = sqrtLanes(L::select(missed, zero, disc));
  const F32 q = b + bitsAs<F32>((bitsAs<I32>(root) & ~signBit) | (bitsAs<I32>(b) & signBit));
  F32 t0 = c / q, t1 = q / a;
  const I32 tangent = q == 0;  // both roots 0: from the surface, along the tangent
  t0 = L::select(tangent, zero, t0);
  t1 = L::select(tangent, zero, t1);
  const I32 swap = t0 > t1;
  const F32 near = L::select(swap, t1, t0), far = L::select(swap, t0, t1);
  const F32 t = L::select((near > r.tMin) & (near < r.tMax), near,
                          L::select((far > r.tMin) & (far < r.tMax), far, L::splat(kInfinity)));
  return L::store(r.valid & ~missed & (t < r.tMax), t, zero, zero, first, hits);
}

// intersectQuad (shapes.cpp) line by line, branches turned into selects: for quads whose normal
// squares within float's range (quadNormalInRange), the only ones given to the lanes.
template <class F32, class I32>
[[gnu::always_inline]] inline uint32_t quadLanes(const Quad& q, const RayLanes& rays, int first,
                                                 LaneHits& hits) {
  using L = Lanes<F32, I32>;
  const L r(rays, first);
  const Vec3f n = cross(q.edge1, q.edge2);
  const Vec3f &e1 = q.edge1, &e2 = q.edge2;
  const F32 denom = n.x * r.d[0] + n.y * r.d[1] + n.z * r.d[2];
  const F32 cx = q.corner.x - r.o[0], cy = q.corner.y - r.o[1], cz = q.corner.z - r.o[2];
  const F32 t = (cx * n.x + cy * n.y + cz * n.z) / denom;
  const I32 inRange = (denom != 0) & (t > r.tMin) & (t < r.tMax);
  // ray.at(t) − corner
  const F32 rx = (r.o[0] + r.d[0] * t) - q.corner.x, ry = (r.o[1] + r.d[1] * t) - q.corner.y,
            rz = (r.o[2] + r.d[2] * t) - q.corner.z;
  const float nn = dot(n, n);
  const F32 alpha = ((ry * e2.z - rz * e2.y) * n.x + (rz * e2.x - rx * e2.z) * n.y +
                     (rx * e2.y - ry * e2.x) * n.z) /
                    nn;
  const F32 beta = ((e1.y * rz - e1.z * ry) * n.x + (e1.z * rx - e1.x * rz) * n.y +
                    (e1.x * ry - e1.y * rx) * n.z) /
                   nn;
  // As the scalar test: a NaN coordinate fails none of the four comparisons.
  const I32 outside = (alpha < 0) | (alpha > 1) | (beta < 0) | (beta > 1);
  return L::store(r.valid & inRange & ~outside, t, alpha, beta, first, hits);
}

// Lanes [0, n) of a packet, n a multiple of F32's lanes.
template <class F32, class I32, class Sqrt>
[[gnu::always_inline]] inline uint32_t sphereBlocks(const Sphere& s, const RayLanes& rays, int n,
                                                    LaneHits& hits, Sqrt sqrtLanes) {
  uint32_t bits = 0;
  for (int first = 0; first < n; first += Lanes<F32, I32>::W)
    bits |= sphereLanes<F32, I32>(s, rays, first, hits, sqrtLanes);
  return bits;
}
template <class F32, class I32>
[[gnu::always_inline]] inline uint32_t quadBlocks(const Quad& q, const RayLanes& rays, int n,
                                                  LaneHits& hits) {
  uint32_t bits = 0;
  for (int first = 0; first < n; first += Lanes<F32, I32>::W)
    bits |= quadLanes<F32, I32>(q, rays, first, hits);
  return bits;
}

}  // namespace
}  // namespace glint
