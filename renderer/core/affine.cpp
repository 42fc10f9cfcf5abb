#include "core/affine.h"

#include <cmath>
#include <stdexcept>

namespace glint {

Mat4 afterTranslation(const Mat4& m, const Vec3d& t) {
  Mat4 r = m;
  for (int i = 0; i < 4; ++i)
    r(i, 3) = static_cast<float>(double(m(i, 3)) + m(i, 0) * t.x + m(i, 1) * t.y + m(i, 2) * t.z);
  return r;
}

Affine Affine::translate(const Vec3d& t) {
  Affine a;
  a.m_[3] = t.x;
  a.m_[7] = t.y;
  a.m_[11] = t.z;
  return a;
}

Affine Affine::scale(const Vec3d& s) {
  Affine a;
  a.m_[0] = s.x;
  a.m_[5] = s.y;
  a.m_[10] = s.z;
  return a;
}

Affine Affine::rotate(const Vec3d& axis, double degrees) {
  const double len = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
  if (!(len > 0)) throw std::invalid_argument("the rotation axis has zero length");
  const double x = axis.x / len, y = axis.y / len, z = axis.z / len;
  const double rad = degrees * 3.14159265358979323846 / 180.0;
  double s = std::sin(rad), c = std::cos(rad);
  if (std::fabs(s) < 1e-15) s = 0;
  if (std::fabs(c) < 1e-15) c = 0;
  const double t = 1 - c;
  return fromRows({t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0,  //
                   t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0,  //
                   t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0});
}

Affine Affine::fromRows(const std::array<double, 12>& rows) {
  Affine a;
  a.m_ = rows;
  return a;
}

Affine operator*(const Affine& a, const Affine& b) {
  Affine r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = j == 3 ? a.m_[size_t(i * 4 + 3)] : 0.0;
      for (int k = 0; k < 3; ++k) s += a.m_[size_t(i * 4 + k)] * b.m_[size_t(k * 4 + j)];
      r.m_[size_t(i * 4 + j)] = s;
    }
  return r;
}

Vec3d Affine::point(const Vec3d& p) const {
  const auto row = [&](int i) {
    const double* r = &m_[size_t(i * 4)];
    return r[0] * p.x + r[1] * p.y + r[2] * p.z + r[3];
  };
  return {row(0), row(1), row(2)};
}

Transform Affine::toTransform() const {
  Mat4 m;
  for (size_t i = 0; i < 12; ++i) m.m[i] = static_cast<float>(m_[i]);
  return Transform(m);
}

}  // namespace glint
