#pragma once
// A ray o + t·d valid for t in (tMin, tMax), at a shutter time in [0, 1] (Embree's range).
#include <cmath>
#include <cstdint>

#include "core/vec.h"

namespace glint {

struct Ray {
  Vec3f o;
  Vec3f d;
  float tMin = 0;
  float tMax = kInfinity;
  float time = 0;

  Vec3f at(float t) const { return o + t * d; }
};

// γ(n) = nε/(1 − nε), ε = 2⁻²⁴: the relative error bound of n float operations (Higham;
// pbrt-v4 §6.8). Error bounds on computed points are built from it.
constexpr float gamma(int n) {
  constexpr float kEps = 0x1p-24f;
  return (float(n) * kEps) / (1 - float(n) * kEps);
}

// Moves p off its surface so that a ray leaving towards `w` cannot hit that surface again:
// the offset along the geometric normal ng is the projection of p's error bound pError onto
// ng, and each coordinate is then rounded one more ulp away (pbrt-v4's OffsetRayOrigin). The
// offset scales with the magnitudes that produced p, so it is as small as the numbers allow at
// every scale and distance from the origin.
inline Vec3f offsetRayOrigin(const Vec3f& p, const Vec3f& pError, const Vec3f& ng, const Vec3f& w) {
  const float d = dot(abs(ng), pError);
  Vec3f offset = d * ng;
  if (dot(w, ng) < 0) offset = -offset;
  Vec3f po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0)
      po[i] = std::nextafter(po[i], kInfinity);
    else if (offset[i] < 0)
      po[i] = std::nextafter(po[i], -kInfinity);
  }
  return po;
}

}  // namespace glint
