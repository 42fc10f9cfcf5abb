#pragma once
// Warps from the unit square to the shapes that effects sample.
#include <cmath>

#include "core/vec.h"

namespace glint {

// Shirley–Chiu concentric map to the unit disk: keeps strata compact and area-preserving.
inline Vec2f squareToDiskConcentric(Vec2f u) {
  const float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
  if (ox == 0 && oy == 0) return {0, 0};
  float r, theta;
  if (std::fabs(ox) > std::fabs(oy)) {
    r = ox;
    theta = (kPi / 4) * (oy / ox);
  } else {
    r = oy;
    theta = kPi / 2 - (kPi / 4) * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

}  // namespace glint
