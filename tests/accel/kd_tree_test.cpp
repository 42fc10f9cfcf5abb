// The k-d tree's depth bound and reference budget (seed 000 §12.3.4), on scenes built for them.
#include "accel/kd_tree.h"

#include <gtest/gtest.h>

#include <cmath>

#include "accel/triangle_scenes.h"

namespace glint {
namespace {

using test::triangles;

TEST(KdTree, SeparatesScatteredTrianglesWithinItsDepthBound) {
  // 1000 small triangles: the SAH cuts until leaves hold a few; depth stays within
  // 8 + 1.3·log₂(1000) = 20.9, and straddling triangles are listed on both sides, which the
  // SAH keeps rare with planes between 1/100-wide triangles (well under 3 per triangle).
  const Scene s = triangles(1000, false);
  const KdTree tree(s);
  EXPECT_LE(tree.stats().maxDepth, size_t(8 + 1.3 * std::log2(1000.0)));
  EXPECT_GT(tree.stats().leaves, 100u);
  EXPECT_LT(tree.stats().referencesPerPrimitive(), 3.0);
}

TEST(KdTree, ReferencesStayBoundedWhenEveryPrimitiveSpansTheScene) {
  // 20 000 triangles each spanning the cube's diagonal: planes cut empty corners off, but every
  // plane through the middle lists almost every triangle twice. The budget (64 per primitive
  // plus 2²⁰) holds, and the closest hit is still found.
  const Scene s = triangles(20000, true);
  const KdTree tree(s);
  EXPECT_LE(double(tree.stats().references), 64.0 * 20000 + (1 << 20));
  test::expectFindsTheFansClosestHit(s, tree);
}

}  // namespace
}  // namespace glint
