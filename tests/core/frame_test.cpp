// The orthonormal basis of core/frame.h, at the poles, on the equator and in between.
#include "core/frame.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Frame, OrthonormalAndRightHandedForEveryNormal) {
  // Unit normals over the sphere, the poles (n.z = ±1, where the construction's sign flips)
  // and a normal just below the equator included. Each product is a few roundings from exact.
  std::vector<Vec3f> normals = {
      {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0.9999999f, -1e-4f}};
  for (int i = 0; i < 200; ++i) {
    const float z = -1 + 2 * (float(i) + 0.5f) / 200, phi = 2.4f * float(i);
    const float r = std::sqrt(1 - z * z);
    normals.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  for (const Vec3f& n : normals) {
    Vec3f t, b;
    orthonormalBasis(n, t, b);
    EXPECT_NEAR(length(t), 1, 1e-6);
    EXPECT_NEAR(length(b), 1, 1e-6);
    EXPECT_NEAR(dot(t, b), 0, 1e-6);
    EXPECT_NEAR(dot(t, n), 0, 1e-6);
    EXPECT_NEAR(dot(b, n), 0, 1e-6);
    EXPECT_NEAR(dot(cross(t, b), n), 1, 1e-6);  // right-handed
  }
}

}  // namespace
}  // namespace glint
