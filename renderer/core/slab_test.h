#pragma once
// The ray–box slab test shared by every hierarchy and grid (the reference BVH, the uniform grid)
// and by CSG's operand culling.
#include <algorithm>
#include <cmath>

#include "core/bounds.h"
#include "core/ray.h"

namespace glint {

// The reciprocal of a ray's direction and the signs of its components, for slabTest.
struct RaySlabs {
  Vec3f inv;
  int negative[3];
  explicit RaySlabs(const Ray& ray)
      : inv{1.0f / ray.d.x, 1.0f / ray.d.y, 1.0f / ray.d.z},
        negative{std::signbit(inv.x), std::signbit(inv.y), std::signbit(inv.z)} {}
};

// Narrows [tNear, tFar] to the part of `ray` inside `box`; true when some of it is left.
// Williams et al. 2005: 1/±0 = ±∞ by IEEE, and the slab planes are taken in the order the ray
// meets them (by the sign of its direction), so the near distance only ever raises tNear and the
// far one only lowers tFar. An origin exactly on a slab plane of a ray parallel to it gives 0·∞ =
// NaN; std::max(tNear, NaN) and std::min(tFar, NaN) keep their first argument, so that slab simply
// does not constrain the ray. Ize 2013: the far distance times 1 + 2γ₃ makes the float test
// conservative (2 ulps).
inline bool slabTest(const Bounds3f& box, const Ray& ray, const RaySlabs& s, float& tNear,
                     float& tFar) {
  constexpr float kMachineEpsilon = 0x1p-24f;
  constexpr float kSlabPad = 1 + 2 * (3 * kMachineEpsilon) / (1 - 3 * kMachineEpsilon);
  const Vec3f* planes = &box.lo;  // planes[0] = lo, planes[1] = hi
  for (int a = 0; a < 3; ++a) {
    const float tn = (planes[s.negative[a]][a] - ray.o[a]) * s.inv[a];
    const float tf = (planes[1 - s.negative[a]][a] - ray.o[a]) * s.inv[a];
    tNear = std::max(tNear, tn);
    tFar = std::min(tFar, tf * kSlabPad);
  }
  return tNear <= tFar;
}

}  // namespace glint
