#include "geometry/triangulate.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace glint
