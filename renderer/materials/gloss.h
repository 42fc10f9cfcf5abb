#pragma once
// Glossy reflection and blurred translucency (seed 000 §13.4.4, seed 002 §9.3): the ideal
// direction is perturbed over a small square orthogonal to it, one sample per camera sample.
#include "core/frame.h"
#include "core/vec.h"

namespace glint {

// r' = normalize(r + (u₁ − ½)·a·e₁ + (u₂ − ½)·a·e₂) for unit r, with (e₁, e₂) r's tangents and
// `a` the square's width; u in [0, 1)².
inline Vec3f perturb(const Vec3f& r, float a, Vec2f u) {
  Vec3f e1, e2;
  orthonormalBasis(r, e1, e2);
  return normalize(r + (a * (u.x - 0.5f)) * e1 + (a * (u.y - 0.5f)) * e2);
}

}  // namespace glint
