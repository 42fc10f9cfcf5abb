#pragma once
// The lane kernel behind intersectSphereLanes, written once over GNU vector types and compiled
// three times, each in its own file with its own instruction set (sphere_lanes*.cpp): the
// anonymous namespace gives each file its own copy, so the linker cannot swap an AVX-512 copy
// into the SSE2 build. Include only from those files.
#include <bit>
#include <cstring>
#include <limits>

#include "geometry/sphere_lanes.h"

namespace glint {
namespace {

// Lanes [first, first + W) of `rays` against s, W the lanes of F32 (I32: as many int32_t):
// intersectSphere (shapes.cpp) line by line, branches turned into selects. `sqrtLanes` is the
// file's square root of F32 (GNU vectors have none). Returns the hit lanes as bits.
template <class F32, class I32, class Sqrt>
[[gnu::always_inline]] inline uint32_t sphereLanes(const Sphere& s, const RayLanes& rays, int first,
                                                   float* tHit, Sqrt sqrtLanes) {
  constexpr int W = sizeof(F32) / sizeof(float);
  const auto loadF = [first](const float* p) {
    F32 v;
    std::memcpy(&v, p + first, sizeof v);
    return v;
  };
  const auto select = [](I32 mask, F32 a, F32 b) {
    return std::bit_cast<F32>((mask & std::bit_cast<I32>(a)) | (~mask & std::bit_cast<I32>(b)));
  };
  I32 validLanes;
  std::memcpy(&validLanes, rays.valid + first, sizeof validLanes);
  const I32 valid = validLanes != 0;
  // Ignored lanes trace a harmless ray (origin 0, direction (1, 1, 1)) so that whatever Embree
  // left in them cannot raise a floating-point exception.
  const F32 zero = F32{} + 0.0f, one = zero + 1.0f;
  const F32 ox = select(valid, loadF(rays.o[0]), zero), oy = select(valid, loadF(rays.o[1]), zero),
            oz = select(valid, loadF(rays.o[2]), zero);
  const F32 dx = select(valid, loadF(rays.d[0]), one), dy = select(valid, loadF(rays.d[1]), one),
            dz = select(valid, loadF(rays.d[2]), one);
  const F32 tMin = loadF(rays.tMin), tMax = loadF(rays.tMax);

  const F32 fx = ox - s.center.x, fy = oy - s.center.y, fz = oz - s.center.z;
  const F32 a = dx * dx + dy * dy + dz * dz;
  const F32 b = -(fx * dx + fy * dy + fz * dz);
  const F32 ba = b / a;
  const F32 lx = fx + dx * ba, ly = fy + dy * ba, lz = fz + dz * ba;
  const float r2 = s.radius * s.radius;
  const F32 disc = a * (r2 - (lx * lx + ly * ly + lz * lz));
  const I32 missed = disc < 0;
  const F32 c = (fx * fx + fy * fy + fz * fz) - r2;
  // std::copysign(sqrt, b): the magnitude's bits with b's sign bit. A missed lane's root is of
  // 0, not of a negative number (no invalid-operation flag); its result is discarded.
  const I32 signBit = I32{} + std::numeric_limits<int32_t>::min();
  const F32 root = sqrtLanes(select(missed, zero, disc));
  const F32 q = b + std::bit_cast<F32>((std::bit_cast<I32>(root) & ~signBit) |
                                       (std::bit_cast<I32>(b) & signBit));
  F32 t0 = c / q, t1 = q / a;
  const I32 through = q == 0;  // ray through the centre with the origin on the surface
  t0 = select(through, zero, t0);
  t1 = select(through, zero, t1);
  const I32 swap = t0 > t1;
  const F32 near = select(swap, t1, t0), far = select(swap, t0, t1);
  const F32 inf = zero + kInfinity;
  const F32 t =
      select((near > tMin) & (near < tMax), near, select((far > tMin) & (far < tMax), far, inf));
  const I32 hit = valid & ~missed & (t < tMax);
  std::memcpy(tHit + first, &t, sizeof t);
  uint32_t bits = 0;
  for (int l = 0; l < W; ++l) bits |= hit[l] ? 1u << (first + l) : 0u;
  return bits;
}

}  // namespace
}  // namespace glint
