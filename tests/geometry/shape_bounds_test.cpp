// A shape's box holds the whole shape, though its corners are computed in float.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/shapes.h"

namespace glint {
namespace {

// `box` holds [lo, hi] along `axis`, compared in double (the true extent need not be a float).
void expectHolds(const Bounds3f& box, int axis, double lo, double hi) {
  EXPECT_LE(double(box.lo[axis]), lo) << "axis " << axis;
  EXPECT_GE(double(box.hi[axis]), hi) << "axis " << axis;
}

TEST(ShapeBounds, ASmallSphereFarFromTheOriginIsInsideItsBox) {
  // Centre 10⁵ out, radius 10⁻³: floats there are 2⁻⁷ ≈ 0.0078 apart, so c ± r rounds to c and
  // the plain box had no depth at all; the sphere reaches 10⁻³ either side of it.
  const Sphere s{{0.3f, -0.2f, -1e5f}, 1e-3f};
  const Bounds3f box = bounds(s);
  expectHolds(box, 0, 0.3f - 1e-3, 0.3f + 1e-3);
  expectHolds(box, 1, -0.2f - 1e-3, -0.2f + 1e-3);
  expectHolds(box, 2, -1e5 - 1e-3, -1e5 + 1e-3);
  // And not much more: two or three float steps (0.0078 each) at 10⁵.
  EXPECT_LT(double(box.hi.z) - double(box.lo.z), 0.1);
}

TEST(ShapeBounds, AQuadAndADiskFarFromTheOriginAreInsideTheirBoxes) {
  // A quad whose far corner, 10⁵ + 10⁻³ in exact arithmetic, rounds to 10⁵ in float.
  const Quad q{{1e5f, 0, 0}, {1e-3f, 0, 0}, {0, 1, 0}};
  expectHolds(bounds(q), 0, 1e5, 1e5 + 1e-3);
  // One whose far corner (c + e₁) + e₂ is 0.3 exactly but 0.296875 in float: the sum c + e₁
  // rounded at 10⁵'s float spacing, far above 0.3's.
  const Quad far{{-1e5f, 0, 0}, {0.3f, 0, 0}, {1e5f, 1, 0}};
  expectHolds(bounds(far), 0, -1e5, double(0.3f));
  // A disk facing x: it reaches its radius along y and z, and nothing along x.
  const Disk d{{0, 1e5f, 0}, {1, 0, 0}, 1e-3f};
  expectHolds(bounds(d), 1, 1e5 - 1e-3, 1e5 + 1e-3);
  expectHolds(bounds(d), 2, -1e-3, 1e-3);
}

TEST(ShapeBounds, AShapeReachingInfinityKeepsItsFiniteSidesFinite) {
  // A sphere at 3.4·10³⁸ of that radius reaches past the largest float: its box's far side is
  // +∞, and growing the near side by the axis's largest coordinate must not make it −∞ (a box
  // of ±∞ has a NaN centre, which crashed the BVH's binning).
  const Bounds3f box = bounds(Sphere{{3.4e38f, 0, -3.4e38f}, 3.4e38f});
  EXPECT_EQ(box.hi.x, kInfinity);
  EXPECT_TRUE(std::isfinite(box.lo.x));
  EXPECT_TRUE(std::isfinite(box.hi.z));
  EXPECT_EQ(box.lo.z, -kInfinity);
  // One of radius FLT_MAX at the origin stays within ±FLT_MAX.
  const Bounds3f widest = bounds(Sphere{{0, 0, 0}, std::numeric_limits<float>::max()});
  EXPECT_TRUE(std::isfinite(widest.lo.y) && std::isfinite(widest.hi.y));
}

}  // namespace
}  // namespace glint
