#pragma once
// What shading needs to know about a hit, in world space, rebuilt from a Hit by shared code
// (Scene::shadingPoint) so that no integrator ever reads a backend's own structures.
#include <cstdint>

#include "core/ray.h"
#include "geometry/hit.h"

namespace glint {

struct ShadingPoint {
  Vec3f p;       // on the surface, computed from the primitive (not from o + t·d)
  Vec3f pError;  // per-coordinate bound on |p − true point| (float rounding)
  Vec3f ng;      // unit geometric normal, as the primitive defines it (not flipped)
  Vec3f ns;      // unit shading normal, same side as ng
  float t = 0;
  uint32_t materialId = 0;
  uint32_t objectId = 0;
};

// The one way to make a secondary or shadow ray: leaves the surface on the side `dir` points
// to, offset by p's error bound (offsetRayOrigin).
inline Ray spawnRay(const ShadingPoint& sp, const Vec3f& dir, float time) {
  Ray r;
  r.o = offsetRayOrigin(sp.p, sp.pError, sp.ng, dir);
  r.d = dir;
  r.time = time;
  return r;
}

// A shadow ray towards a point: t in (0, 1) covers the segment and stops just short of the
// target, by a relative 2^-12 of the segment, so the light's own surface never occludes it.
inline Ray spawnRayTo(const ShadingPoint& sp, const Vec3f& target, float time) {
  Ray r = spawnRay(sp, target - sp.p, time);
  r.d = target - r.o;
  r.tMax = 1.0f - 1.0f / 4096.0f;
  return r;
}

}  // namespace glint
