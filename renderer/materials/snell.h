#pragma once
// The direction light takes through a dielectric interface (seed 001 §7): Snell's law
// η_i sinθ_i = η_t sinθ_t, with total internal reflection explicit.
#include <algorithm>
#include <cmath>

#include "core/vec.h"

namespace glint {

// Refracts unit d through a surface whose unit normal n faces against d (dot(d, n) ≤ 0), with
// eta = η_i / η_t: t = η d + (η cosθ_i − cosθ_t) n. False under total internal reflection
// (sin²θ_t ≥ 1), where no light crosses.
inline bool refract(const Vec3f& d, const Vec3f& n, float eta, Vec3f& t) {
  const float cosI = std::clamp(-dot(d, n), 0.0f, 1.0f);
  const float sin2T = eta * eta * std::max(0.0f, 1 - cosI * cosI);
  if (sin2T >= 1) return false;
  const float cosT = std::sqrt(1 - sin2T);
  t = normalize(eta * d + (eta * cosI - cosT) * n);
  return true;
}

}  // namespace glint
