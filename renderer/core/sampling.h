#pragma once
// Warps from the unit square to the shapes that effects sample.
#include <cmath>

#include "core/vec.h"

namespace glint {

// sin φ and cos φ for |φ| ≤ π/4, by their Taylor series to φ⁹ and φ¹⁰: the truncation errors
// (φ¹¹/11!, φ¹²/12! at π/4) are below 2e-9, far under float's rounding, and unlike sincosf there
// is no range reduction and no call. F: a float, or floats side by side in a GNU vector (the
// same operations in the same order, so each lane gives the float's bits).
template <class F>
[[gnu::always_inline]] inline void cosSinQuarterPi(const F& phi, F& c, F& s) {
  const F x2 = phi * phi;
  s = phi *
      (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 +
                                                   x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800)))));
}
inline Vec2f cosSinQuarterPi(float phi) {
  Vec2f cs;
  cosSinQuarterPi(phi, cs.x, cs.y);
  return cs;
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

// squareToDiskConcentric of points side by side (F: a GNU vector of floats), lane by lane the
// same bits: both wedges' quotient and polynomial in every lane, the lane's wedge selected.
// Vectors pass by reference and cast in place: Clang refuses a 32-byte vector passed by value
// between an AVX2 clone and a function built without AVX, inlined or not.
template <class F>
[[gnu::always_inline]] inline void squareToDiskConcentricLanes(const F& ux, const F& uy, F& dx,
                                                               F& dy) {
  using Mask = decltype(ux < uy);
  const F ox = 2.0f * ux - 1.0f, oy = 2.0f * uy - 1.0f;
  const Mask magnitude = Mask{} + 0x7fffffff;  // every bit but the sign
  const F absX = (F)((Mask)ox & magnitude);
  const F absY = (F)((Mask)oy & magnitude);
  const Mask alongX = absX > absY;
  const F r = alongX ? ox : oy;
  F c, s;
  cosSinQuarterPi((kPi / 4) * ((alongX ? oy : ox) / r), c, s);
  const Mask centre = (ox == 0) & (oy == 0);
  dx = centre ? F{} : alongX ? r * c : r * s;
  dy = centre ? F{} : alongX ? r * s : r * c;
}

}  // namespace glint
