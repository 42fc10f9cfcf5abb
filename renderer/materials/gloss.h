#pragma once
// Glossy reflection and blurred translucency (seed 000 §13.4.4, seed 002 §9.3): the ideal
// direction is spread over a lobe, one sample per camera sample. Two lobes: seed 000's square
// of width a orthogonal to the ideal direction, and seed 002's specular distribution function,
// the Phong lobe cosⁿ α about it.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/frame.h"
#include "core/vec.h"

namespace glint {

// Which lobe a material's gloss (or blur) number sizes: the square's width, or the Phong lobe's
// exponent n.
enum class GlossShape : uint8_t { Square, Phong };

// Whether a lobe of this shape and size spreads rays at all: a square of width 0 is the ideal
// direction, while every Phong lobe spreads (n = 0 is the whole hemisphere about it).
inline bool spreads(GlossShape shape, float size) { return shape == GlossShape::Phong || size > 0; }

// r' = normalize(r + (u₁ − ½)·a·e₁ + (u₂ − ½)·a·e₂) for unit r, with (e₁, e₂) r's tangents and
// `a` the square's width; u in [0, 1)².
inline Vec3f perturb(const Vec3f& r, float a, Vec2f u) {
  Vec3f e1, e2;
  orthonormalBasis(r, e1, e2);
  return normalize(r + (a * (u.x - 0.5f)) * e1 + (a * (u.y - 0.5f)) * e2);
}

// A direction drawn from the normalised Phong lobe (n + 1)/(2π)·cosⁿ α about unit r, α the
// angle to r, for u in [0, 1)²: cos α = u₁^(1/(n+1)) inverts the lobe's distribution of cos α,
// P(cos α ≤ c) = c^(n+1), and φ = 2π·u₂ is uniform about r. Since the rays are drawn in
// proportion to the lobe, each carries the same weight, and their mean is the lobe-weighted
// mean of the radiance they bring back.
inline Vec3f samplePhongLobe(const Vec3f& r, float n, Vec2f u) {
  const float cosA = std::pow(u.x, 1 / (n + 1));
  const float sinA = std::sqrt(std::max(0.0f, 1 - cosA * cosA));
  const float phi = 2 * kPi * u.y;
  Vec3f e1, e2;
  orthonormalBasis(r, e1, e2);
  return (sinA * std::cos(phi)) * e1 + (sinA * std::sin(phi)) * e2 + cosA * r;
}

// The ideal direction r spread by a lobe of `shape` sized `size`, with the sample u.
inline Vec3f spread(const Vec3f& r, GlossShape shape, float size, Vec2f u) {
  return shape == GlossShape::Phong ? samplePhongLobe(r, size, u) : perturb(r, size, u);
}

}  // namespace glint
