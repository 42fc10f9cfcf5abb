#pragma once
// Axis-aligned bounding box in whatever space its points live in.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/vec.h"

namespace glint {

struct Bounds3f {
  Vec3f lo{kInfinity, kInfinity, kInfinity};
  Vec3f hi{-kInfinity, -kInfinity, -kInfinity};

  void extend(const Vec3f& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void extend(const Bounds3f& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  // Corner c in [0, 8): bits 0, 1, 2 pick hi (set) or lo (clear) along x, y, z.
  Vec3f corner(int c) const {
    return {(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
  }
  Vec3f diagonal() const { return hi - lo; }
};

// `b` grown on both sides of each axis by 2⁻²² of the axis's largest coordinate (two float
// steps of it or more). A shape's box computed in float (a centre ± a radius, a corner + edges)
// rounds to the nearest float, which may lie inside the shape's true extent: a sphere of radius
// 10⁻³ centred 10⁵ from the origin, where floats are 0.008 apart, got a box of zero depth, and
// rays from beside it missed a sphere that Embree (traversing more conservatively) hit. The
// largest coordinate, not each side's own, bounds the rounding: a quad's far corner (c + e₁) +
// e₂ = 0.3 from c = −10⁵ carries the rounding of 10⁵, and c is a corner of the box too.
inline Bounds3f roundedOutward(const Bounds3f& b) {
  constexpr float kMax = std::numeric_limits<float>::max();
  Bounds3f out = b;
  for (int a = 0; a < 3; ++a) {
    const float pad = std::min(std::max(std::abs(b.lo[a]), std::abs(b.hi[a])), kMax) * 0x1p-22f;
    // A finite side stays finite: the structures take a box's centre, which ±∞ on both sides
    // makes NaN (tests/fuzz/regressions/bvh-centroid-overflow.json: a sphere reaching +∞).
    if (std::isfinite(b.lo[a])) out.lo[a] = std::max(b.lo[a] - pad, -kMax);
    if (std::isfinite(b.hi[a])) out.hi[a] = std::min(b.hi[a] + pad, kMax);
  }
  return out;
}

}  // namespace glint
