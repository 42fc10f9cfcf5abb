#include "materials/texture.h"

#include <cmath>

namespace glint {

namespace {

// ⌊x⌋ as an integer, clamped to ±2^62 (NaN gives −2^62): std::floor is a libm call on baseline
// x86-64, and converting a double beyond the integer range is undefined.
long long floorToInteger(double x) {
  constexpr double kLimit = 0x1p62;
  if (!(std::fabs(x) < kLimit)) return x > 0 ? (1LL << 62) : -(1LL << 62);
  const auto i = static_cast<long long>(x);  // truncates towards zero
  return static_cast<double>(i) > x ? i - 1 : i;
}

}  // namespace

Rgb ColorTexture::checkerAt(const Vec3f& renderP, const Vec3d& worldOrigin) const {
  const Vec3d p = toDouble(renderP) + worldOrigin;
  // A tiny bias keeps a plane lying exactly on a cell boundary (y = 0) on one side of it.
  constexpr double kBias = 1e-4;
  const auto cell = [&](double x) { return floorToInteger(x / scale + kBias); };
  return ((cell(p.x) + cell(p.y) + cell(p.z)) & 1) ? b : a;
}

}  // namespace glint
