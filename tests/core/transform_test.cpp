#include "core/transform.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Transform, RotateNinetyAboutYTakesXToMinusZ) {
  // Right-handed rotation by +90° about y: x̂ → −ẑ, ẑ → x̂ (exact: sin and cos snap to 0 and 1).
  const Transform r = Transform::rotate({0, 1, 0}, 90);
  const Vec3f x = r.vector({1, 0, 0});
  EXPECT_FLOAT_EQ(x.x, 0);
  EXPECT_FLOAT_EQ(x.z, -1);
  const Vec3f z = r.vector({0, 0, 1});
  EXPECT_FLOAT_EQ(z.x, 1);
  EXPECT_FLOAT_EQ(z.z, 0);
}

TEST(Transform, ScaleThenRotateThenTranslateOrder) {
  // SCENE_FORMAT.md: scale, then rotate, then translate. (1,0,0) → scale 2 → (2,0,0) →
  // rotate 90° about z → (0,2,0) → translate (1,1,1) → (1,3,1).
  const Transform t = Transform::translate({1, 1, 1}) * Transform::rotate({0, 0, 1}, 90) *
                      Transform::scale({2, 2, 2});
  const Vec3f p = t.point({1, 0, 0});
  EXPECT_NEAR(p.x, 1, 1e-6);
  EXPECT_NEAR(p.y, 3, 1e-6);
  EXPECT_NEAR(p.z, 1, 1e-6);
  const Vec3f back = t.inverse().point(p);
  EXPECT_NEAR(back.x, 1, 1e-6);
  EXPECT_NEAR(back.y, 0, 1e-6);
}

TEST(Transform, NormalsUseInverseTranspose) {
  // Plane x + y = 0 has normal (1,1,0). Scaling x by 2 maps it to x/2 + y = 0, whose normal is
  // (0.5, 1, 0): the inverse transpose, not the matrix itself (which would give (2, 1, 0)).
  const Transform s = Transform::scale({2, 1, 1});
  const Vec3f n = s.normal({1, 1, 0});
  EXPECT_FLOAT_EQ(n.x, 0.5f);
  EXPECT_FLOAT_EQ(n.y, 1);
  EXPECT_FLOAT_EQ(n.z, 0);
}

TEST(Transform, SimilarityDetection) {
  float k = 0;
  EXPECT_TRUE((Transform::rotate({1, 2, 3}, 37) * Transform::scale({3, 3, 3})).isSimilarity(&k));
  EXPECT_NEAR(k, 3, 1e-5);
  EXPECT_FALSE(Transform::scale({1, 2, 1}).isSimilarity());
}

TEST(Transform, SingularMatrixIsRejected) {
  Mat4 m;
  m(1, 1) = 0;  // flattens y
  EXPECT_THROW(Transform{m}, std::invalid_argument);
}

}  // namespace
}  // namespace glint
