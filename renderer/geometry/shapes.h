#pragma once
// Analytic shapes and their ray intersection, shared by every backend (Embree user geometry,
// brute force, and later the reference BVH) so that backends differ only in traversal.
#include "core/bounds.h"
#include "core/ray.h"

namespace glint {

struct Sphere {
  Vec3f center;
  float radius = 1;
};

// Parallelogram corner + α·edge1 + β·edge2, α, β in [0, 1]; normal = edge1 × edge2.
struct Quad {
  Vec3f corner, edge1, edge2;
};

// A flat disk: the points of the plane through `center` with unit `normal` within `radius`.
struct Disk {
  Vec3f center, normal;
  float radius = 1;
};

// Infinite plane through `point`; `normal` is unit length.
struct Plane {
  Vec3f point, normal;
};

// Each returns the nearest t in (ray.tMin, ray.tMax) or a value ≥ ray.tMax (kInfinity) on a
// miss; (u, v) are written only on a hit.
float intersectSphere(const Sphere& s, const Ray& ray);
// Where the ray's whole line meets the sphere, t0 ≤ t1, whatever tMin and tMax say; false when
// it misses (CSG needs both ends of the inside interval, wherever the ray starts).
bool sphereRoots(const Sphere& s, const Ray& ray, float& t0, float& t1);
float intersectQuad(const Quad& q, const Ray& ray, float& u, float& v);
// Whether q's normal (edge1 × edge2) squares within float's normal range, where intersectQuad
// takes the formula quadLanes (geometry/shape_lanes_kernel.h) follows; others are tested one
// ray at a time.
bool quadNormalInRange(const Quad& q);
// Inline: the batched plane loops (accel/accelerator.cpp) run it once a ray and plane.
inline float intersectPlane(const Plane& p, const Ray& ray) {
  const float denom = dot(p.normal, ray.d);
  if (denom == 0) return kInfinity;
  const float t = dot(p.point - ray.o, p.normal) / denom;
  return (t > ray.tMin && t < ray.tMax) ? t : kInfinity;
}
float intersectDisk(const Disk& d, const Ray& ray);
// Watertight ray–triangle test (Woop, Benthin, Wald 2013), Embree's barycentric convention.
float intersectTriangle(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Ray& ray, float& u,
                        float& v);

Bounds3f bounds(const Sphere& s);
Bounds3f bounds(const Quad& q);
Bounds3f bounds(const Disk& d);

}  // namespace glint
