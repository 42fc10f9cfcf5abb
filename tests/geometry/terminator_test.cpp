// The lift of shadow-ray origins towards a smooth mesh's surface (geometry/terminator.h).
#include "geometry/terminator.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

// The octant triangle of the unit sphere: vertices on the axes, exact sphere normals (their
// positions), seen at its centroid p = (1/3, 1/3, 1/3).
constexpr float kThird = 1.0f / 3.0f;
const Vec3f kVertices[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const float kCentroid[3] = {kThird, kThird, kThird};
const Vec3f kP{kThird, kThird, kThird};

TEST(Terminator, ConvexFacetIsLiftedOntoItsVerticesTangentPlanes) {
  // p lies 2/3 below each vertex's tangent plane (dot(p − v_i, v_i) = 1/3 − 1): each moves it
  // by (1/3)·(2/3) along v_i, so the lift is 2/9 on every axis and p + lift = (5/9)(1, 1, 1),
  // at distance 0.962 from the centre where p is at 0.577: much closer to the sphere.
  const Vec3f lift = smoothSurfaceLift(kP, kVertices, kVertices, kCentroid, {1, 1, 1});
  EXPECT_NEAR(lift.x, 2.0f / 9, 1e-6f);
  EXPECT_NEAR(lift.y, 2.0f / 9, 1e-6f);
  EXPECT_NEAR(lift.z, 2.0f / 9, 1e-6f);
  EXPECT_NEAR(length(kP + lift), 5.0f / 9 * std::sqrt(3.0f), 1e-6f);
}

TEST(Terminator, FlatOrConcaveOrInwardFacetsAreNotLifted) {
  // Flat: every vertex normal is the facet's, p lies on each tangent plane (up to rounding).
  const Vec3f face = normalize(Vec3f{1, 1, 1});
  const Vec3f flat[3] = {face, face, face};
  const Vec3f none = smoothSurfaceLift(kP, kVertices, flat, kCentroid, face);
  EXPECT_LT(length(none), 1e-6f);
  // Leaving to the inside of the sphere, the normals turn to that side: p is 2/3 above each
  // tangent plane, so nothing moves it out of the sphere (a concave bowl seen from inside alike).
  const Vec3f inward = smoothSurfaceLift(kP, kVertices, kVertices, kCentroid, {-1, -1, -1});
  EXPECT_EQ(inward, (Vec3f{0, 0, 0}));
}

}  // namespace
}  // namespace glint
