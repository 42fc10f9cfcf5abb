#pragma once
// The binned surface-area heuristic (Wald 2007) shared by the hierarchies that use it (the
// reference BVH and the sphere hierarchy): centroids mapped to B bins along an axis, and the
// cheapest cut between bins (traversal cost 1, intersection cost 1).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/bounds.h"

namespace glint {

inline float surfaceArea(const Bounds3f& b) {
  if (b.empty()) return 0;
  const Vec3f d = b.diagonal();
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// Maps a centroid coordinate in [lo, hi] to one of B bins. It works on halved coordinates: for
// centroids near ±3.4e38, hi − lo overflowed, (c − lo)·B/∞ was NaN and the NaN, cast to int,
// indexed outside the bins (found by tests/fuzz). Halving is exact, so every bin is the one that
// (c − lo)·B/(hi − lo) gives whenever that is finite.
template <int B>
class CentroidBins {
 public:
  CentroidBins(float lo, float hi) : halfLo_(0.5f * lo), scale_(B / (0.5f * hi - halfLo_)) {}
  // False when the bins cannot separate anything: a zero or non-finite extent.
  bool usable() const { return std::isfinite(scale_) && scale_ > 0; }
  int operator()(float c) const {
    return std::min(B - 1, static_cast<int>((0.5f * c - halfLo_) * scale_));
  }

 private:
  float halfLo_, scale_;
};

// The cut after bin `bin` (bins ≤ bin on the left) of least A(left)·N(left) + A(right)·N(right)
// with both sides holding something, the first of equal costs: its bin and cost, or −1 (and ∞)
// when no cut separates anything.
template <int B>
int cheapestCut(const Bounds3f (&bins)[B], const size_t (&counts)[B], float& cost) {
  float rightArea[B];
  size_t rightCount[B];
  Bounds3f acc;
  size_t n = 0;
  for (int b = B - 1; b > 0; --b) {
    acc.extend(bins[b]);
    n += counts[b];
    rightArea[b] = surfaceArea(acc);
    rightCount[b] = n;
  }
  acc = Bounds3f{};
  n = 0;
  cost = kInfinity;
  int best = -1;
  for (int b = 0; b < B - 1; ++b) {
    acc.extend(bins[b]);
    n += counts[b];
    const float c = surfaceArea(acc) * float(n) + rightArea[b + 1] * float(rightCount[b + 1]);
    if (n > 0 && rightCount[b + 1] > 0 && c < cost) {
      cost = c;
      best = b;
    }
  }
  return best;
}

}  // namespace glint
