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

}  // namespace
}  // namespace glint
