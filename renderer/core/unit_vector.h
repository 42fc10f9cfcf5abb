#pragma once
// Normalising a direction given at any scale. A scene may write a light's direction as
// [0, -1e20, -1e20], or place a plane by a transform that scales by 1e-20; the squared length
// of such a vector overflows float (or underflows to 0), and normalize() returned zero or NaN:
// the light went dark and the plane vanished, without a word.
#include <algorithm>
#include <cmath>

#include "core/affine.h"
#include "core/vec.h"

namespace glint {

// Whether a's squared length lies well inside float's range (2^-100 to 2^100), so that its
// length, and cross products of it with unit vectors, neither overflow nor underflow.
inline bool hasSafeLength(const Vec3f& a) {
  const float l2 = dot(a, a);
  return l2 >= 0x1p-100f && l2 <= 0x1p100f;
}

// d / |d| for finite, non-zero d (NaN for zero). Where d's float components have a safe
// length, exactly normalize() of them, as directions always were; otherwise in double, d first
// divided by its largest |component| so that no square overflows or underflows.
inline Vec3f unitVector(const Vec3d& d) {
  if (const Vec3f f = toFloat(d); hasSafeLength(f)) return normalize(f);
  const double m = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
  const double x = d.x / m, y = d.y / m, z = d.z / m;
  const double l = std::sqrt(x * x + y * y + z * z);
  return {float(x / l), float(y / l), float(z / l)};
}
inline Vec3f unitVector(const Vec3f& a) { return unitVector(toDouble(a)); }

}  // namespace glint
