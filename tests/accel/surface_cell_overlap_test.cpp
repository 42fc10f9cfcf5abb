// The exact surface–cell tests of accel/surface_cell_overlap.h against cases computed by hand:
// each box below overlaps the primitive's own box, so only the exact test tells them apart.
#include "accel/surface_cell_overlap.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace glint {
namespace {

Bounds3f box(Vec3f lo, Vec3f hi) { return {lo, hi}; }

TEST(SurfaceCellOverlap, SphereSurfaceAgainstBoxes) {
  const Vec3f o{0, 0, 0};
  // A cell deep inside: its farthest corner is √0.03 = 0.17 < 1 from the centre. The surface
  // does not meet it: a full cell.
  EXPECT_EQ(sphereContact(o, 1, box({-0.1f, -0.1f, -0.1f}, {0.1f, 0.1f, 0.1f})),
            CellContact::Inside);
  // A cell straddling the surface: nearest point 0.5, farthest corner √(2.25 + 0.02) = 1.51.
  EXPECT_EQ(sphereContact(o, 1, box({0.5f, -0.1f, -0.1f}, {1.5f, 0.1f, 0.1f})),
            CellContact::Surface);
  // A cell in the corner of the sphere's box, outside the ball: its nearest point
  // (0.6, 0.6, 0.6) is √1.08 = 1.04 > 1 away.
  EXPECT_EQ(sphereContact(o, 1, box({0.6f, 0.6f, 0.6f}, {1, 1, 1})), CellContact::Apart);
  // Moved to (0.55, 0.55, 0.55): √0.9075 = 0.95 < 1, and the far corner √3 > 1.
  EXPECT_EQ(sphereContact(o, 1, box({0.55f, 0.55f, 0.55f}, {1, 1, 1})), CellContact::Surface);
  // The whole sphere inside one cell: the surface meets it.
  EXPECT_EQ(sphereContact(o, 1, box({-2, -2, -2}, {2, 2, 2})), CellContact::Surface);
}

TEST(SurfaceCellOverlap, TriangleBySeparatingAxes) {
  // The triangle (0,0,0), (1,0,0), (0,1,0): its hypotenuse is x + y = 1 in the plane z = 0.
  const Vec3f a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_TRUE(triangleMeetsBox(a, b, c, box({0.2f, 0.2f, -0.1f}, {0.3f, 0.3f, 0.1f})));
  // A box whose corner (0.51, 0.51) lies 0.02 past the hypotenuse (x + y = 1.02): only the
  // axis of the hypotenuse × z separates them (the boxes overlap, the plane cuts the box).
  EXPECT_FALSE(triangleMeetsBox(a, b, c, box({0.51f, 0.51f, -0.1f}, {0.7f, 0.7f, 0.1f})));
  // Its corner at (0.49, 0.49): x + y = 0.98 < 1, inside the triangle.
  EXPECT_TRUE(triangleMeetsBox(a, b, c, box({0.49f, 0.49f, -0.1f}, {0.7f, 0.7f, 0.1f})));
  // Above the plane: the box's z axis separates.
  EXPECT_FALSE(triangleMeetsBox(a, b, c, box({0.1f, 0.1f, 0.1f}, {0.2f, 0.2f, 0.2f})));
  // The tilted triangle (0,0,0), (1,0,1), (0,1,1) lies in z = x + y: over [0.1, 0.2]² the
  // plane is at z ≤ 0.4, below the box [0.6, 0.7] in z, which only its normal tells.
  EXPECT_FALSE(
      triangleMeetsBox(a, {1, 0, 1}, {0, 1, 1}, box({0.1f, 0.1f, 0.6f}, {0.2f, 0.2f, 0.7f})));
  EXPECT_TRUE(
      triangleMeetsBox(a, {1, 0, 1}, {0, 1, 1}, box({0.1f, 0.1f, 0.2f}, {0.2f, 0.2f, 0.3f})));
}

TEST(SurfaceCellOverlap, ParallelogramBySeparatingAxes) {
  // corner 0, edges (1, 0, 0) and (0.5, 1, 0): its left side is x = 0.5·y.
  const Vec3f corner{0, 0, 0}, e1{1, 0, 0}, e2{0.5f, 1, 0};
  // At y = 0.6 the side is at x = 0.3: a box at x ≤ 0.15 lies left of it.
  EXPECT_FALSE(
      parallelogramMeetsBox(corner, e1, e2, box({0.05f, 0.6f, -0.1f}, {0.15f, 0.7f, 0.1f})));
  // (0.35, 0.65) is right of the side (x = 0.325 there) and left of the right side (1.325).
  EXPECT_TRUE(parallelogramMeetsBox(corner, e1, e2, box({0.3f, 0.6f, -0.1f}, {0.4f, 0.7f, 0.1f})));
  // Its right side is x = 1 + 0.5·y, at most 1.1 for y ≤ 0.2: a box at x ≥ 1.2 lies right of
  // it (inside the parallelogram's box, which reaches x = 1.5).
  EXPECT_FALSE(
      parallelogramMeetsBox(corner, e1, e2, box({1.2f, 0.05f, -0.1f}, {1.4f, 0.2f, 0.1f})));
}

TEST(SurfaceCellOverlap, DiskByPlaneThenCircle) {
  const Vec3f o{0, 0, 0};
  // Radius 1 in the plane z = 0: the cut of the box is the square [0.6, 1]², nearest corner
  // (0.6, 0.6) at 0.85.
  EXPECT_TRUE(diskMeetsBox(o, {0, 0, 1}, 1, box({0.6f, 0.6f, -0.1f}, {1, 1, 0.1f})));
  // The plane misses the box (z ≥ 0.05), though the ball of radius 1 reaches it (0.5 away).
  EXPECT_FALSE(diskMeetsBox(o, {0, 0, 1}, 1, box({0.5f, -0.1f, 0.05f}, {1.5f, 0.1f, 1})));
  // The plane z = −x cuts the tall box [0.9, 1.1] × [−0.05, 0.05] × [−2, 2] at x ≥ 0.9,
  // z ≤ −0.9, at least √1.62 = 1.27 from the centre: the circle misses, though the ball
  // reaches the box (its nearest point (0.9, 0, 0) is 0.9 away) and the plane cuts it.
  const Vec3f n = normalize(Vec3f{1, 0, 1});
  EXPECT_FALSE(diskMeetsBox(o, n, 1, box({0.9f, -0.05f, -2}, {1.1f, 0.05f, 2})));
  // Radius 1.3 reaches it.
  EXPECT_TRUE(diskMeetsBox(o, n, 1.3f, box({0.9f, -0.05f, -2}, {1.1f, 0.05f, 2})));
}

TEST(SurfaceCellOverlap, PadsTheCellForRounding) {
  // A unit sphere and a cell 10⁻⁶ beyond its surface: exactly apart, but within the pad
  // (10⁻⁴ of the cell's side 1 and 2⁻¹⁸ of its coordinate 2: 1.08·10⁻⁴), so a hit rounded a
  // hair outside the sphere is still found in the cell.
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const PrimitiveBox p{bounds(s.spheres[0]), 0, 0};
  const Bounds3f near = box({1 + 1e-6f, -0.5f, -0.5f}, {2, 0.5f, 0.5f});
  EXPECT_EQ(sphereContact({0, 0, 0}, 1, near), CellContact::Apart);
  EXPECT_EQ(surfaceContact(s, 0, p, near), CellContact::Surface);
  // 10⁻³ beyond is past the pad.
  EXPECT_EQ(surfaceContact(s, 0, p, box({1.001f, -0.5f, -0.5f}, {2, 0.5f, 0.5f})),
            CellContact::Apart);
  // A cell deep inside is full.
  EXPECT_EQ(surfaceContact(s, 0, p, box({-0.1f, -0.1f, -0.1f}, {0.1f, 0.1f, 0.1f})),
            CellContact::Inside);
}

}  // namespace
}  // namespace glint
