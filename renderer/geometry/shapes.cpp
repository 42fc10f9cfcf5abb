#include "geometry/shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace glint {

bool sphereRoots(const Sphere& s, const Ray& ray, float& t0, float& t1) {
  // Ray Tracing Gems ch. 7 (Haines et al.): the discriminant from the distance of the centre to
  // the ray line, and the near root from c/q, avoid the cancellation of the textbook formula.
  const Vec3f f = ray.o - s.center;
  const float a = dot(ray.d, ray.d);
  const float b = -dot(f, ray.d);  // half of the usual b, negated
  const Vec3f l = f + (b / a) * ray.d;
  const float r2 = s.radius * s.radius;
  const float disc = a * (r2 - dot(l, l));
  if (disc < 0) return false;
  const float c = dot(f, f) - r2;
  const float q = b + std::copysign(std::sqrt(disc), b);
  t0 = c / q, t1 = q / a;
  if (q == 0) t0 = t1 = 0;  // ray through the centre with the origin on the surface
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

float intersectSphere(const Sphere& s, const Ray& ray) {
  float t0, t1;
  if (!sphereRoots(s, ray, t0, t1)) return kInfinity;
  if (t0 > ray.tMin && t0 < ray.tMax) return t0;
  if (t1 > ray.tMin && t1 < ray.tMax) return t1;
  return kInfinity;
}

bool quadNormalInRange(const Quad& q) {
  const Vec3f n = cross(q.edge1, q.edge2);
  const float nn = dot(n, n);
  return nn >= std::numeric_limits<float>::min() && nn <= std::numeric_limits<float>::max();
}

float intersectQuad(const Quad& q, const Ray& ray, float& u, float& v) {
  const Vec3f n = cross(q.edge1, q.edge2);
  // The plane's normal m: n itself, or, where n squares out of float's range (edges past about
  // 10^9.5, where α and β would be ∞/∞ = NaN and the hit a NaN point, or under 10^-9.5), n over
  // its largest coordinate, which leaves t, α and β as they are. For m = n the operations are
  // quadLanes' (the same bits).
  Vec3f m = n;
  if (!quadNormalInRange(q)) [[unlikely]] {
    const float largest = maxComponent(abs(n));
    if (!(largest > 0) || !std::isfinite(largest)) return kInfinity;  // no plane to meet
    m = {n.x / largest, n.y / largest, n.z / largest};
  }
  const float denom = dot(m, ray.d);
  if (denom == 0) return kInfinity;
  const float t = dot(q.corner - ray.o, m) / denom;
  if (!(t > ray.tMin && t < ray.tMax)) return kInfinity;
  const Vec3f rel = ray.at(t) - q.corner;
  const float nm = dot(n, m);
  const float alpha = dot(cross(rel, q.edge2), m) / nm;
  const float beta = dot(cross(q.edge1, rel), m) / nm;
  if (alpha < 0 || alpha > 1 || beta < 0 || beta > 1) return kInfinity;
  u = alpha;
  v = beta;
  return t;
}

float intersectDisk(const Disk& d, const Ray& ray) {
  const float denom = dot(d.normal, ray.d);
  if (denom == 0) return kInfinity;
  const float t = dot(d.center - ray.o, d.normal) / denom;
  if (!(t > ray.tMin && t < ray.tMax)) return kInfinity;
  const Vec3f rel = ray.at(t) - d.center;
  return dot(rel, rel) <= d.radius * d.radius ? t : kInfinity;
}

float intersectTriangle(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Ray& ray, float& u,
                        float& v) {
  // Permute so the direction's largest component is z, shear to +z, then 2D edge functions;
  // edges shared by two triangles give consistent signs, so no ray slips between them.
  int kz = 0;
  const Vec3f ad = abs(ray.d);
  if (ad.y > ad[kz]) kz = 1;
  if (ad.z > ad[kz]) kz = 2;
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (ray.d[kz] < 0) std::swap(kx, ky);
  const float sx = ray.d[kx] / ray.d[kz], sy = ray.d[ky] / ray.d[kz], sz = 1.0f / ray.d[kz];
  const Vec3f a = p0 - ray.o, b = p1 - ray.o, c = p2 - ray.o;
  const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  // Edge functions in float; exactly zero means the ray passes through an edge or vertex, where
  // float rounding could disagree between neighbours, so those are recomputed in double.
  float U = cx * by - cy * bx, V = ax * cy - ay * cx, W = bx * ay - by * ax;
  if (U == 0 || V == 0 || W == 0) {
    U = static_cast<float>(double(cx) * by - double(cy) * bx);
    V = static_cast<float>(double(ax) * cy - double(ay) * cx);
    W = static_cast<float>(double(bx) * ay - double(by) * ax);
  }
  if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return kInfinity;
  const float det = U + V + W;
  if (det == 0) return kInfinity;
  const float T = U * (sz * a[kz]) + V * (sz * b[kz]) + W * (sz * c[kz]);
  const float invDet = 1.0f / det;
  const float t = T * invDet;
  if (!(t > ray.tMin && t < ray.tMax)) return kInfinity;
  u = V * invDet;
  v = W * invDet;
  return t;
}

Bounds3f bounds(const Sphere& s) {
  const Vec3f r{s.radius, s.radius, s.radius};
  return roundedOutward({s.center - r, s.center + r});
}

Bounds3f bounds(const Quad& q) {
  Bounds3f b;
  b.extend(q.corner);
  b.extend(q.corner + q.edge1);
  b.extend(q.corner + q.edge2);
  b.extend(q.corner + q.edge1 + q.edge2);
  return roundedOutward(b);
}

Bounds3f bounds(const Disk& d) {
  // Per axis the disk reaches radius·sin of the angle between the axis and the normal,
  // √(1 − n_i²); padded by a relative 2^-20 for the rounding of these terms.
  const Vec3f n2 = mul(d.normal, d.normal);
  const auto reach = [&](float ni2) {
    return d.radius * std::sqrt(std::max(0.0f, 1 - ni2)) * (1 + 0x1p-20f);
  };
  const Vec3f e{reach(n2.x), reach(n2.y), reach(n2.z)};
  return roundedOutward({d.center - e, d.center + e});
}

}  // namespace glint
