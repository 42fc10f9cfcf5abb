#pragma once
// Axis-aligned bounding box in whatever space its points live in.
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

}  // namespace glint
