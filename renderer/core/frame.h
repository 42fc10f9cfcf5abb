#pragma once
// An orthonormal basis around a unit vector: the tangent frame that glossy lobes perturb
// directions in and that disk lights spread their points over.
#include <cmath>

#include "core/vec.h"

namespace glint {

// Unit tangents t and b with (t, b, n) right-handed and orthonormal, for unit n. Duff et al.,
// "Building an Orthonormal Basis, Revisited" (JCGT 2017): no branch on a chosen axis, so the
// frame turns continuously with n everywhere but across n.z = 0's sign change.
inline void orthonormalBasis(const Vec3f& n, Vec3f& t, Vec3f& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace glint
