#include "materials/material.h"

#include <cmath>

namespace glint {

Rgb ColorTexture::eval(const Vec3f& renderP, const Vec3d& worldOrigin) const {
  if (!checker) return constant;
  const Vec3d p = toDouble(renderP) + worldOrigin;
  // A tiny bias keeps a plane lying exactly on a cell boundary (y = 0) on one side of it.
  constexpr double kBias = 1e-4;
  const auto cell = [&](double x) { return static_cast<long long>(std::floor(x / scale + kBias)); };
  return ((cell(p.x) + cell(p.y) + cell(p.z)) & 1) ? b : a;
}

}  // namespace glint
