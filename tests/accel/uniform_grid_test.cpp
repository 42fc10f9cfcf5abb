// The uniform grid's resolution rule and its bound on references, on scenes built for them.
#include "accel/uniform_grid.h"

#include <gtest/gtest.h>

#include "accel/triangle_scenes.h"

namespace glint {
namespace {

using test::triangles;

TEST(UniformGrid, ResolutionIsTheCubeRootOfThePrimitiveCount) {
  // Seed 002 §9.2.1: R = ⌈∛n⌉ cells per axis; 1000 triangles: 10³ cells.
  const Scene s = triangles(1000, false);
  const UniformGrid grid(s);
  EXPECT_EQ(grid.stats().cells, 1000u);
  EXPECT_EQ(grid.stats().primitives, 1000u);
  // Triangles 1/100 of the cube wide in cells 1/10 wide: most fall in one cell, a few straddle.
  EXPECT_LT(grid.stats().references, 1500u);
  // Exactly ⌈∛n⌉ where ∛n is a whole number: cbrt(27.0) is 3.0000000000000004 in double.
  EXPECT_EQ(UniformGrid(triangles(27, false)).stats().cells, 27u);
  EXPECT_EQ(UniformGrid(triangles(28, false)).stats().cells, 64u);
}

TEST(UniformGrid, ReferencesStayBoundedWhenEveryPrimitiveSpansTheScene) {
  // 20 000 triangles, each spanning the cube: at ⌈∛n⌉ = 28 cells per axis each would be listed
  // in 28³ = 21 952 cells (4.4·10⁸ references, 1.7 GB). The grid halves its resolution until
  // they fit in 64 per primitive plus 2²⁰: 28 → 14 → 7 → 3 cells per axis, 27 per triangle.
  const Scene s = triangles(20000, true);
  const UniformGrid grid(s);
  EXPECT_LE(double(grid.stats().references), 64.0 * 20000 + (1 << 20));
  EXPECT_EQ(grid.stats().cells, 27u);
  // And it still finds the closest hit.
  test::expectFindsTheFansClosestHit(s, grid);
}

TEST(UniformGrid, ListsASphereOnlyInTheCellsItsSurfaceMeets) {
  // A unit sphere in 5 × 5 × 5 cells 0.4 wide (faces at ±0.2, ±0.6, ±1). Its box reaches all
  // 125. Per axis a cell's farthest coordinate is 0.2, 0.6 or 1 from the centre and its nearest
  // 0, 0.2 or 0.6: the cells whose farthest corner is within 1 lie inside (the centre cell,
  // 0.12; its 6 face neighbours, 0.44; the 12 at (0.6, 0.6, 0.2), 0.76), the 8 corner cells,
  // nearest at √1.08 = 1.04, lie outside: 125 − 19 − 8 = 98 cells hold part of the surface.
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const UniformGrid grid(s, 5);
  EXPECT_EQ(grid.stats().cells, 125u);
  EXPECT_EQ(grid.stats().references, 98u);
  // A ray from the centre, inside the centre cell whose list is empty, finds the surface.
  const Hit h = grid.intersect(Ray{{0, 0, 0}, normalize(Vec3f{0.3f, 0.5f, 0.8f})});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h.t, 1, 1e-6);
}

}  // namespace
}  // namespace glint
