#include "core/motion.h"

#include <cmath>
#include <stdexcept>

namespace glint {

Quat Quat::fromAxisAngle(const Vec3f& axis, float degrees) {
  const float len = length(axis);
  if (!(len > 0)) throw std::invalid_argument("the rotation axis has zero length");
  const double half = double(degrees) * 3.14159265358979323846 / 360.0;
  const float s = static_cast<float>(std::sin(half)) / len;
  return {static_cast<float>(std::cos(half)), axis.x * s, axis.y * s, axis.z * s};
}

Mat4 Quat::toMatrix() const {
  Mat4 m;
  m(0, 0) = 1 - 2 * (y * y + z * z);
  m(0, 1) = 2 * (x * y - w * z);
  m(0, 2) = 2 * (x * z + w * y);
  m(1, 0) = 2 * (x * y + w * z);
  m(1, 1) = 1 - 2 * (x * x + z * z);
  m(1, 2) = 2 * (y * z - w * x);
  m(2, 0) = 2 * (x * z - w * y);
  m(2, 1) = 2 * (y * z + w * x);
  m(2, 2) = 1 - 2 * (x * x + y * y);
  return m;
}

Quat slerp(const Quat& a, const Quat& bIn, float t) {
  Quat b = bIn;
  float cosTheta = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
  if (cosTheta < 0) {  // q and −q are the same rotation: take the shorter arc
    b = {-b.w, -b.x, -b.y, -b.z};
    cosTheta = -cosTheta;
  }
  float wa, wb;
  if (cosTheta > 0.9995f) {
    wa = 1 - t;
    wb = t;
  } else {
    const float theta = std::acos(std::min(cosTheta, 1.0f));
    const float sinTheta = std::sin(theta);
    wa = std::sin((1 - t) * theta) / sinTheta;
    wb = std::sin(t * theta) / sinTheta;
  }
  Quat q{wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z};
  const float n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}

Transform TrsKey::toTransform() const {
  return Transform::translate(translation) * Transform(rotation.toMatrix()) *
         Transform::scale(scale);
}

TrsKey lerp(const TrsKey& a, const TrsKey& b, float t) {
  return {(1 - t) * a.scale + t * b.scale, slerp(a.rotation, b.rotation, t),
          (1 - t) * a.translation + t * b.translation};
}

}  // namespace glint
