#pragma once
// Warps from the unit square to the shapes that effects sample.
#include <cmath>

#include "core/vec.h"

namespace glint {

// sin φ and cos φ for |φ| ≤ π/4, by their Taylor series to φ⁹ and φ¹⁰: the truncation errors
// (φ¹¹/11!, φ¹²/12! at π/4) are below 2e-9, far under float's rounding, and unlike sincosf there
// is no range reduction and no call.
inline Vec2f cosSinQuarterPi(float phi) {
  const float x2 = phi * phi;
  const float s =
      phi * (1 + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const float c =
      1 + x2 * (-0.5f + x2 * (1.0f / 24 +
                              x2 * (-1.0f / 720 + x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800)))));
  return {c, s};
}

// Shirley–Chiu concentric map to the unit disk: keeps strata compact and area-preserving. The
// angle is π/4·(oy/ox) in the wedges around ±x and π/2 − π/4·(ox/oy) around ±y, whose cosine
// and sine are the sine and cosine of π/4·(ox/oy).
inline Vec2f squareToDiskConcentric(Vec2f u) {
  const float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
  if (ox == 0 && oy == 0) return {0, 0};
  if (std::fabs(ox) > std::fabs(oy)) {
    const Vec2f cs = cosSinQuarterPi((kPi / 4) * (oy / ox));
    return {ox * cs.x, ox * cs.y};
  }
  const Vec2f cs = cosSinQuarterPi((kPi / 4) * (ox / oy));
  return {oy * cs.y, oy * cs.x};
}

}  // namespace glint
