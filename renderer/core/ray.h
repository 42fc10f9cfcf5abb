#pragma once
// A ray o + t·d valid for t in (tMin, tMax), at a shutter time in [0, 1] (Embree's range).
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/vec.h"

namespace glint {

// Where a ray comes from (Ray::origin), for the backend that classifies rays by the object they
// leave (ray coherence, accel/ray_coherence.h); every other backend ignores it. An entry of the
// world group (a hit's geomId, or its instId inside an instance) for a ray leaving that entry's
// surface; the eye for a camera ray; light k for a shadow ray towards light k (a segment that
// ends on the light at t = 1 when the light has a finite position).
// It is a hint: the backend checks the ray against the origin's bounds and takes its fallback
// when they disagree, so a missing or wrong tag costs time, never a hit.
namespace ray_origin {
inline constexpr uint32_t kNone = 0xFFFFFFFFu;
inline constexpr uint32_t kEye = 0xFFFFFFFEu;
inline constexpr uint32_t kLightBit = 0x80000000u;  // below it: a world entry
constexpr uint32_t light(size_t k) { return kLightBit | static_cast<uint32_t>(k); }
}  // namespace ray_origin

struct Ray {
  Vec3f o;
  Vec3f d;
  float tMin = 0;
  float tMax = kInfinity;
  float time = 0;
  uint32_t origin = ray_origin::kNone;

  Vec3f at(float t) const { return o + t * d; }
};

// Embree 3.13 asserts (an abort, in Debian's build) on a ray whose origin or direction has a
// coordinate past FLT_LARGE = 1.844e18, whose tnear is below 0 or NaN, tfar NaN, or time outside
// [0, 1] (kernels/common/ray.h RayK::valid, asserted by every BVH traversal, an instance's
// object-space ray included). Glint keeps what it builds within 1e18 of 0 in render space:
// geometry, camera rays, the rays of `validate` (accel/embree_accel.cpp guards the rest).
inline constexpr float kEmbreeMaxRayCoordinate = 1.844e18f;
inline constexpr float kMaxRayOrigin = 1e18f;

// Whether every coordinate of `v` is within ±kMaxRayOrigin (false for NaN): a point that may
// start rays, or a direction, that Embree takes.
inline bool withinRayRange(const Vec3f& v) {
  return std::fabs(v.x) <= kMaxRayOrigin && std::fabs(v.y) <= kMaxRayOrigin &&
         std::fabs(v.z) <= kMaxRayOrigin;
}

// γ(n) = nε/(1 − nε), ε = 2⁻²⁴: the relative error bound of n float operations (Higham;
// pbrt-v4 §6.8). Error bounds on computed points are built from it.
constexpr float gamma(int n) {
  constexpr float kEps = 0x1p-24f;
  return (float(n) * kEps) / (1 - float(n) * kEps);
}

// The float after x towards +∞ (nextFloatUp) or −∞ (nextFloatDown): std::nextafter(x, ±∞),
// which on x86-64 is a call into libm, in a few integer operations on the bit pattern.
inline float nextFloatUp(float x) {
  if (!(x < kInfinity)) return x;                            // +∞ and NaN stay
  if (x == 0) return std::bit_cast<float>(1u);               // ±0: the smallest subnormal
  const auto bits = std::bit_cast<uint32_t>(x);              // the magnitude grows for x > 0,
  return std::bit_cast<float>(x > 0 ? bits + 1 : bits - 1);  // shrinks for x < 0
}
inline float nextFloatDown(float x) { return -nextFloatUp(-x); }

// p + offset, each coordinate then rounded one more ulp in the offset's direction:
// offsetRayOrigin's last step.
[[gnu::always_inline]] inline Vec3f offsetAway(const Vec3f& p, const Vec3f& offset) {
  const Vec3f po = p + offset;
  // Per coordinate, not through po[i]: indexing kept po in memory (store forwarding).
  const auto away = [](float x, float o) {
    return o > 0 ? nextFloatUp(x) : o < 0 ? nextFloatDown(x) : x;
  };
  return {away(po.x, offset.x), away(po.y, offset.y), away(po.z, offset.z)};
}

// Moves p off its surface so that a ray leaving towards `w` cannot hit that surface again:
// the offset along the geometric normal ng is the projection of p's error bound pError onto
// ng, and each coordinate is then rounded one more ulp away (pbrt-v4's OffsetRayOrigin). The
// offset scales with the magnitudes that produced p, so it is as small as the numbers allow at
// every scale and distance from the origin.
[[gnu::always_inline]] inline Vec3f offsetRayOrigin(const Vec3f& p, const Vec3f& pError,
                                                    const Vec3f& ng, const Vec3f& w) {
  Vec3f offset = dot(abs(ng), pError) * ng;
  if (dot(w, ng) < 0) offset = -offset;
  return offsetAway(p, offset);
}

}  // namespace glint
