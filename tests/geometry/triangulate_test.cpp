#include "geometry/triangulate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

float area(const std::vector<Vec3f>& v, const std::vector<uint32_t>& tris, Vec3f normal) {
  float a = 0;
  for (size_t i = 0; i < tris.size(); i += 3) {
    const Vec3f n = cross(v[tris[i + 1]] - v[tris[i]], v[tris[i + 2]] - v[tris[i]]);
    EXPECT_GT(dot(n, normal), 0) << "triangle " << i / 3 << " is flipped";
    a += 0.5f * length(n);
  }
  return a;
}

TEST(Triangulate, ConcaveLShape) {
  // An L of three unit squares in the z = 1 plane, counter-clockwise seen from +z: area 3,
  // 6 vertices → 4 triangles, none flipped, none outside the L.
  const std::vector<Vec3f> v = {{0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1, 1, 1}, {1, 2, 1}, {0, 2, 1}};
  std::vector<uint32_t> tris;
  ASSERT_TRUE(triangulatePolygon(v, tris));
  EXPECT_EQ(tris.size(), 12u);
  EXPECT_NEAR(area(v, tris, {0, 0, 1}), 3.0f, 1e-6);
}

TEST(Triangulate, ClockwiseWindingIsKept) {
  // The same square listed clockwise: triangles keep the polygon's (−z) orientation.
  const std::vector<Vec3f> v = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  std::vector<uint32_t> tris;
  ASSERT_TRUE(triangulatePolygon(v, tris));
  EXPECT_NEAR(area(v, tris, {0, 0, -1}), 1.0f, 1e-6);
}

TEST(Triangulate, DegenerateIsRefused) {
  std::vector<uint32_t> tris;
  EXPECT_FALSE(triangulatePolygon({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, tris));  // collinear
  EXPECT_FALSE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}}, tris));
}

TEST(Triangulate, AHundredThousandVertexStarIsTriangulatedWhole) {
  // Alternate vertices at radius 1 and 0.9 around a circle: 50 000 reflex vertices. Once 35 s
  // of ear search that rescanned the whole ring for every ear; now each ear is tested against the
  // reflex vertices near it. n − 2 triangles, none flipped, covering the star's area: the sum
  // over its n spokes of ½·1·0.9·sin(2π/n) (float coordinates and sums: 1e-4 relative).
  constexpr int n = 100000;
  std::vector<Vec3f> v;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, r = i % 2 ? 0.9 : 1.0;
    v.push_back({float(r * std::cos(a)), float(r * std::sin(a)), 0});
  }
  std::vector<uint32_t> tris;
  ASSERT_TRUE(triangulatePolygon(v, tris));
  EXPECT_EQ(tris.size(), 3u * (n - 2));
  double area = 0;
  for (size_t i = 0; i < tris.size(); i += 3) {
    const Vec3f e = cross(v[tris[i + 1]] - v[tris[i]], v[tris[i + 2]] - v[tris[i]]);
    EXPECT_GE(e.z, 0) << "triangle " << i / 3 << " is flipped";
    area += 0.5 * double(e.z);
  }
  const double expected = n * 0.5 * 0.9 * std::sin(2 * M_PI / n);
  EXPECT_NEAR(area, expected, 1e-4 * expected);
}

TEST(Triangulate, AConvexPolygonFromVertexZeroKeepsItsFirstEar) {
  // A square clips its first ear at vertex 0, (3, 0, 1), and then the rest (1, 2, 3): the order
  // the triangles of quads and boxes have always had.
  const std::vector<Vec3f> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<uint32_t> tris;
  ASSERT_TRUE(triangulatePolygon(v, tris));
  EXPECT_EQ(tris, (std::vector<uint32_t>{3, 0, 1, 1, 2, 3}));
}

}  // namespace
}  // namespace glint
