#include "core/transform.h"

#include <stdexcept>

#include "core/affine.h"
#include "core/ray.h"

namespace glint {

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      float s = 0;
      for (int k = 0; k < 4; ++k) s += a(i, k) * b(k, j);
      r(i, j) = s;
    }
  return r;
}

bool invert(const Mat4& a, Mat4& out) {
  // Gauss-Jordan with partial pivoting in double: exact enough for scene transforms.
  double w[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      w[i][j] = a(i, j);
      w[i][j + 4] = i == j ? 1.0 : 0.0;
    }
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(w[r][c]) > std::fabs(w[pivot][c])) pivot = r;
    if (std::fabs(w[pivot][c]) < 1e-300) return false;
    for (int j = 0; j < 8; ++j) std::swap(w[c][j], w[pivot][j]);
    const double inv = 1.0 / w[c][c];
    for (int j = 0; j < 8; ++j) w[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = w[r][c];
      for (int j = 0; j < 8; ++j) w[r][j] -= f * w[c][j];
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out(i, j) = static_cast<float>(w[i][j + 4]);
  return true;
}

Transform::Transform(const Mat4& m) : m_(m) {
  if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 2) != 0 || m(3, 3) != 1)
    throw std::invalid_argument("the last row must be [0, 0, 0, 1] (affine transforms only)");
  for (float x : m.m)
    if (!std::isfinite(x)) throw std::invalid_argument("the matrix has a non-finite entry");
  if (!invert(m, inv_)) throw std::invalid_argument("the matrix is singular");
  for (float x : inv_.m)
    if (!std::isfinite(x)) throw std::invalid_argument("the matrix is numerically singular");
}

Transform Transform::translate(const Vec3f& t) {
  Mat4 m;
  m(0, 3) = t.x;
  m(1, 3) = t.y;
  m(2, 3) = t.z;
  return Transform(m);
}

Transform Transform::scale(const Vec3f& s) {
  Mat4 m;
  m(0, 0) = s.x;
  m(1, 1) = s.y;
  m(2, 2) = s.z;
  return Transform(m);
}

Transform Transform::rotate(const Vec3f& axis, float degrees) {
  // Built in double (Rodrigues), so 90° turns land on exact zeros where they can.
  return Affine::rotate(toDouble(axis), degrees).toTransform();
}

float Transform::determinant() const {
  const Mat4& m = m_;
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

Transform Transform::inverse() const {
  Transform t;
  t.m_ = inv_;
  t.inv_ = m_;
  return t;
}

bool Transform::isSimilarity(float* uniformScale) const {
  // Columns of a similarity's linear part are orthogonal with one common length.
  Vec3f c[3];
  for (int j = 0; j < 3; ++j) c[j] = {m_(0, j), m_(1, j), m_(2, j)};
  const float l0 = length(c[0]), l1 = length(c[1]), l2 = length(c[2]);
  const float tol = 1e-5f * l0;
  const bool ok = std::fabs(l0 - l1) <= tol && std::fabs(l0 - l2) <= tol &&
                  std::fabs(dot(c[0], c[1])) <= tol * l0 &&
                  std::fabs(dot(c[0], c[2])) <= tol * l0 && std::fabs(dot(c[1], c[2])) <= tol * l0;
  if (ok && uniformScale) *uniformScale = l0;
  return ok;
}

Vec3f Transform::point(const Vec3f& p) const {
  return {m_(0, 0) * p.x + m_(0, 1) * p.y + m_(0, 2) * p.z + m_(0, 3),
          m_(1, 0) * p.x + m_(1, 1) * p.y + m_(1, 2) * p.z + m_(1, 3),
          m_(2, 0) * p.x + m_(2, 1) * p.y + m_(2, 2) * p.z + m_(2, 3)};
}

Vec3f Transform::pointError(const Vec3f& p, const Vec3f& e) const {
  Vec3f out;
  for (int r = 0; r < 3; ++r) {
    const float absMp = std::fabs(m_(r, 0) * p.x) + std::fabs(m_(r, 1) * p.y) +
                        std::fabs(m_(r, 2) * p.z) + std::fabs(m_(r, 3));
    const float absMe =
        std::fabs(m_(r, 0)) * e.x + std::fabs(m_(r, 1)) * e.y + std::fabs(m_(r, 2)) * e.z;
    out[r] = gamma(3) * absMp + (gamma(3) + 1) * absMe;
  }
  return out;
}

Vec3f Transform::vector(const Vec3f& v) const {
  return {m_(0, 0) * v.x + m_(0, 1) * v.y + m_(0, 2) * v.z,
          m_(1, 0) * v.x + m_(1, 1) * v.y + m_(1, 2) * v.z,
          m_(2, 0) * v.x + m_(2, 1) * v.y + m_(2, 2) * v.z};
}

Vec3f Transform::normal(const Vec3f& n) const {
  return {inv_(0, 0) * n.x + inv_(1, 0) * n.y + inv_(2, 0) * n.z,
          inv_(0, 1) * n.x + inv_(1, 1) * n.y + inv_(2, 1) * n.z,
          inv_(0, 2) * n.x + inv_(1, 2) * n.y + inv_(2, 2) * n.z};
}

Transform operator*(const Transform& a, const Transform& b) {
  Transform t;
  t.m_ = a.m_ * b.m_;
  t.inv_ = b.inv_ * a.inv_;
  return t;
}

Bounds3f transformBox(const Transform& xf, const Bounds3f& b) {
  Bounds3f out;
  for (int c = 0; c < 8; ++c) out.extend(xf.point(b.corner(c)));
  return out;
}

}  // namespace glint
