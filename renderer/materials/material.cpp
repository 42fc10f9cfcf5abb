#include "materials/material.h"

#include <cmath>

namespace glint {

Rgb ColorTexture::eval(const Vec3f& p) const {
  if (!checker) return constant;
  // A tiny bias keeps a plane lying exactly on a cell boundary (y = 0) on one side of it.
  constexpr float kBias = 1e-4f;
  const auto cell = [&](float x) { return static_cast<long long>(std::floor(x / scale + kBias)); };
  return ((cell(p.x) + cell(p.y) + cell(p.z)) & 1) ? b : a;
}

}  // namespace glint
