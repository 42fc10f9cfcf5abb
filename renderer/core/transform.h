#pragma once
// Affine transforms as 4×4 row-major matrices with their inverse kept alongside, so normals can
// be carried by the inverse transpose without inverting per ray.
#include <array>

#include "core/bounds.h"
#include "core/vec.h"

namespace glint {

struct Mat4 {
  std::array<float, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  float operator()(int r, int c) const { return m[static_cast<size_t>(r * 4 + c)]; }
  float& operator()(int r, int c) { return m[static_cast<size_t>(r * 4 + c)]; }
  friend bool operator==(const Mat4&, const Mat4&) = default;
};

Mat4 operator*(const Mat4& a, const Mat4& b);
// Inverse by cofactors in double; returns false when the matrix is singular.
bool invert(const Mat4& a, Mat4& out);

class Transform {
 public:
  Transform() = default;
  // Throws std::invalid_argument when `m` is singular or not affine.
  explicit Transform(const Mat4& m);

  static Transform translate(const Vec3f& t);
  static Transform scale(const Vec3f& s);
  static Transform rotate(const Vec3f& axis, float degrees);

  const Mat4& matrix() const { return m_; }
  const Mat4& inverseMatrix() const { return inv_; }
  Transform inverse() const;
  bool isIdentity() const { return m_ == Mat4{}; }
  // Of the linear part: negative for a mirroring transform.
  float determinant() const;
  // True when the linear part is a rotation times a uniform scale (spheres stay spheres).
  bool isSimilarity(float* uniformScale = nullptr) const;

  Vec3f point(const Vec3f& p) const;
  // The transformed point's error bound, given p's (pbrt-v4 §6.8.6): the rounding of the
  // transform itself plus the propagated input error.
  Vec3f pointError(const Vec3f& p, const Vec3f& pError) const;
  Vec3f vector(const Vec3f& v) const;
  // Normals transform by the inverse transpose; the result is not normalised.
  Vec3f normal(const Vec3f& n) const;

  friend Transform operator*(const Transform& a, const Transform& b);

 private:
  Mat4 m_, inv_;
};

// The box around `b`'s eight corners carried by `xf`.
Bounds3f transformBox(const Transform& xf, const Bounds3f& b);

}  // namespace glint
