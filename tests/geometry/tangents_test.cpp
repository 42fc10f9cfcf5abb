// Generated tangents (geometry/tangents.h): MikkTSpace's frame on meshes without their own.
#include "geometry/tangents.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// A unit square in the xy plane facing +z, its texture turned a quarter: u runs along +y and v
// along −x, so a tangent that merely copied an edge or an axis would point elsewhere.
TriangleMesh turnedSquare(bool mirrored) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  // (u, v) = (y, 1 − x); mirrored: v = x, so +v is +x and the frame is left-handed.
  for (const Vec3f& p : m.positions) m.uvs.push_back({p.y, mirrored ? p.x : 1 - p.x});
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(Tangents, GeneratedTangentsOnAUvMappedSquarePointAlongPlusU) {
  const TriangleMesh m = turnedSquare(false);
  const auto tangents = generateTangents(m);
  ASSERT_EQ(tangents.size(), m.indices.size());  // one per corner
  for (const auto& t : tangents) {
    // dp/du = +y exactly (the square is flat and its mapping affine): float rounding 1e-6.
    EXPECT_NEAR(t.direction.x, 0, 1e-6);
    EXPECT_NEAR(t.direction.y, 1, 1e-6);
    EXPECT_NEAR(t.direction.z, 0, 1e-6);
    // +v is −x = n × t = (+z) × (+y): sign +1.
    EXPECT_EQ(t.sign, 1);
  }
}

TEST(Tangents, AMirroredMappingGetsTheNegativeSign) {
  // +v is +x now, opposite n × t = −x: the bitangent needs sign −1 (glTF's w = −1).
  for (const auto& t : generateTangents(turnedSquare(true))) {
    EXPECT_NEAR(t.direction.y, 1, 1e-6);
    EXPECT_EQ(t.sign, -1);
  }
}

TEST(Tangents, AFlatMeshWithoutCoordinatesTakesEachTrianglesEdgeFromCornerZero) {
  // No normals, no (u, v): Scene maps each triangle's corners to (0,0), (1,0), (0,1), so +u
  // runs from corner 0 to corner 1, here +x.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  m.indices = {0, 1, 2};
  for (const auto& t : generateTangents(m)) {
    EXPECT_NEAR(t.direction.x, 1, 1e-6);
    EXPECT_EQ(t.sign, 1);
  }
}

}  // namespace
}  // namespace glint
