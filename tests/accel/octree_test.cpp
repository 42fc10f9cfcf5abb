// The octree's subdivision rule (seed 002 §9.2.2) and its bound on references, on scenes built
// for them.
#include "accel/octree.h"

#include <gtest/gtest.h>

#include "accel/triangle_scenes.h"

namespace glint {
namespace {

using test::triangles;

TEST(Octree, CutsPartialCellsDownToTheSeedsDepth) {
  // 1000 triangles 1/100 of the cube wide: K = ⌈log₂(1000)/3⌉ = 4 levels (16 cells per axis at
  // the finest, the grid's ⌈∛n⌉ = 10 rounded up to a power of two). At level 3 (512 cells) the
  // average cell holds about 2 triangles, so some hold more and are cut to level 4.
  const Scene s = triangles(1000, false);
  const Octree octree(s);
  EXPECT_EQ(octree.stats().maxDepth, 4u);
  EXPECT_EQ(octree.stats().primitives, 1000u);
  // Only partial cells are cut, so far fewer than the 16³ cells of a full level 4.
  EXPECT_LT(octree.stats().leaves, 4096u);
  // Triangles straddle a mid-plane at the finest level with probability about 3·(1/100)/(1/16):
  // most are listed once.
  EXPECT_LT(octree.stats().references, 2000u);
  // Told to stop at one level, it makes the root and its eight octants.
  const Octree shallow(s, 1);
  EXPECT_EQ(shallow.stats().nodes, 9u);
}

TEST(Octree, DoesNotCutWhatItCannotSeparate) {
  // 50 triangles whose boxes are all the unit cube reach all eight octants of every cell:
  // cutting would list each in every cell and separate nothing, so the root stays one leaf.
  std::string pos, idx;
  for (int t = 0; t < 50; ++t) {
    pos += (t ? "," : "") + test::vec(0, 0, 0) + "," + test::vec(1, 1, 0.2f + 0.005f * float(t)) +
           "," + test::vec(0.3f + 0.002f * float(t), 0.2f, 1);
    idx += (t ? ",[" : "[") + std::to_string(3 * t) + "," + std::to_string(3 * t + 1) + "," +
           std::to_string(3 * t + 2) + "]";
  }
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0.5,0.5,0.5]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "mesh", "material": "m", "positions": [)" +
                                      pos + "], \"indices\": [" + idx + "]}]}");
  const Octree octree(s);
  EXPECT_EQ(octree.stats().nodes, 1u);
  EXPECT_EQ(octree.stats().references, 50u);
}

TEST(Octree, ReferencesStayBoundedWhenEveryPrimitiveSpansTheScene) {
  // 20 000 triangles fanned across the cube (each box spans it in x and y): cut down to the
  // seed's ⌈log₂(20 000)/3⌉ = 5 levels they would be listed in most cells of every level. The
  // octree stops cutting at the budget of 64 per primitive plus 2²⁰, and still finds the
  // closest hit.
  const Scene s = triangles(20000, true);
  const Octree octree(s);
  EXPECT_LE(double(octree.stats().references), 64.0 * 20000 + (1 << 20));
  test::expectFindsTheFansClosestHit(s, octree);
}

}  // namespace
}  // namespace glint
