#pragma once
// A ray o + t·d valid for t in (tMin, tMax), at a shutter time in [0, 1] (Embree's range).
#include <bit>
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

// Moves p off its surface along the geometric normal ng (towards the side the new ray leaves
// on), by an amount that scales with |p|: a fixed number of ulps of each coordinate, and a
// small absolute step near the origin where ulps vanish. This is Wächter & Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6). It assumes p was
// computed from the primitive (barycentrics, re-projection), not from o + t·d.
inline Vec3f offsetRayOrigin(const Vec3f& p, const Vec3f& ng) {
  constexpr float kOrigin = 1.0f / 32.0f;
  constexpr float kFloatScale = 1.0f / 65536.0f;
  constexpr float kIntScale = 256.0f;
  Vec3f out;
  for (int i = 0; i < 3; ++i) {
    const auto ulps = static_cast<int32_t>(kIntScale * ng[i]);
    const auto bits = std::bit_cast<int32_t>(p[i]);
    const float stepped = std::bit_cast<float>(bits + (p[i] < 0 ? -ulps : ulps));
    out[i] = std::fabs(p[i]) < kOrigin ? p[i] + kFloatScale * ng[i] : stepped;
  }
  return out;
}

}  // namespace glint
