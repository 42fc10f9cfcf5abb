#pragma once
// What shading needs to know about a hit, in world space, rebuilt from a Hit by shared code
// (Scene::shadingPoint) so that no integrator ever reads a backend's own structures.
#include <cstdint>

#include "core/ray.h"
#include "core/rgb.h"
#include "geometry/hit.h"

namespace glint {

struct ShadingPoint {
  Vec3f p;       // on the surface, computed from the primitive (not from o + t·d)
  Vec3f pError;  // per-coordinate bound on |p − true point| (float rounding)
  Vec3f ng;      // unit geometric normal, as the primitive defines it (not flipped)
  Vec3f ns;      // unit shading normal, same side as ng
  // Where shadow rays leave from, as an offset from p, when `lifted`: on a smooth-shaded mesh,
  // towards the smooth surface on the side the arriving ray came from (geometry/terminator.h).
  // Other surfaces set only the flag, which each shadow ray reads.
  Vec3f shadowLift;
  bool lifted = false;
  float t = 0;
  uint32_t materialId = 0;
  uint32_t objectId = 0;
  uint32_t origin = ray_origin::kNone;  // the world entry hit: what rays leaving it carry
  // The surface's texture coordinates and their tangents dp/du, dp/dv (world space), filled
  // only on hits whose material reads them (Features::readsCoordinates): every other hit leaves
  // them out.
  Vec2f uv;
  Vec3f dpdu, dpdv;
  // The tangent frame normal maps are read in (materials/normal_map.h), filled only in scenes
  // with normal maps (Features::normalMaps): the tangent along +u (a mesh's interpolated vertex
  // tangent, else dp/du) and the sign that turns ns × tangent towards +v.
  Vec3f tangent;
  float tangentSign = 1;
  // The same for a mesh's second set (glTF's TEXCOORD_1), filled only in scenes with a texture
  // that reads it (Features::secondUvSet); a surface without one has its first set here.
  Vec2f uv1;
  Vec3f dpdu1, dpdv1;
  // The mesh's interpolated vertex colour (white for other shapes), filled only in scenes whose
  // materials use vertex colours (Features::vertexColors).
  Rgb vertexColor;

  // The shading normal on the side of the surface that `w` points to. The side is the
  // geometric normal's to decide: a smooth normal can lean past a direction that ng puts in
  // front (at a silhouette), and must not turn the surface around there.
  Vec3f shadingNormalFacing(const Vec3f& w) const { return dot(ng, w) < 0 ? -ns : ns; }
};

// The one way to make a secondary or shadow ray, written field by field into `r`: leaves the
// surface on the side it heads to, offset by p's error bound (offsetRayOrigin). With
// `toPoint`, `v` is a point and the ray a shadow ray towards it: t in (0, 1) covers the segment
// and stops just short of the point, by a relative 2^-12 of the segment, so the light's own
// surface never occludes it. Otherwise `v` is the direction and the ray unbounded. (Written
// into `r`, not returned: a returned copy stalled on store forwarding.) `origin` is the ray's
// Ray::origin.
inline constexpr float kShadowRayEnd = 1.0f - 1.0f / 4096.0f;
[[gnu::always_inline]] inline void spawnRayFrom(Ray& r, const Vec3f& p, const Vec3f& pError,
                                                const Vec3f& ng, bool toPoint, const Vec3f& v,
                                                float time, uint32_t origin) {
  r.o = offsetRayOrigin(p, pError, ng, toPoint ? v - p : v);
  r.d = toPoint ? v - r.o : v;
  r.tMin = 0;
  r.tMax = toPoint ? kShadowRayEnd : kInfinity;
  r.time = time;
  r.origin = origin;
}
[[gnu::always_inline]] inline void spawnRayInto(Ray& r, const ShadingPoint& sp, bool toPoint,
                                                const Vec3f& v, float time) {
  spawnRayFrom(r, sp.p, sp.pError, sp.ng, toPoint, v, time, sp.origin);
}
// A shadow ray from the point the light is sampled for: from p lifted by sp.shadowLift, whose
// sum p + lift carries one more rounding. The ray carries light `light` as its origin (ray
// coherence classifies a segment that ends on a light at a finite position from that light,
// reversed, and takes its fallback for a light at infinity).
[[gnu::always_inline]] inline void spawnShadowRayInto(Ray& r, const ShadingPoint& sp, bool toPoint,
                                                      const Vec3f& v, float time, size_t light) {
  const uint32_t origin = ray_origin::light(light);
  if (!sp.lifted) [[likely]]
    return spawnRayFrom(r, sp.p, sp.pError, sp.ng, toPoint, v, time, origin);
  const Vec3f from = sp.p + sp.shadowLift;
  spawnRayFrom(r, from, sp.pError + gamma(2) * abs(from), sp.ng, toPoint, v, time, origin);
}
// spawnShadowRayInto for many targets (or directions) from one point: where the shadow rays
// leave from on either side of the surface is worked out once, and each ray only picks its
// side (the same values, bit for bit, as spawnShadowRayInto's).
class ShadowOrigin {
 public:
  explicit ShadowOrigin(const ShadingPoint& sp) : ng_(sp.ng) {
    Vec3f error = sp.pError;
    from_ = sp.p;
    if (sp.lifted) [[unlikely]] {
      from_ = sp.p + sp.shadowLift;
      error = sp.pError + gamma(2) * abs(from_);
    }
    const Vec3f offset = dot(abs(ng_), error) * ng_;
    front_ = offsetAway(from_, offset);
    back_ = offsetAway(from_, -offset);
  }
  [[gnu::always_inline]] void spawnTo(Ray& r, const Vec3f& target, float time,
                                      uint32_t origin) const {
    r.o = dot(target - from_, ng_) < 0 ? back_ : front_;
    r.d = target - r.o;
    r.tMin = 0;
    r.tMax = kShadowRayEnd;
    r.time = time;
    r.origin = origin;
  }
  // spawnShadowRayInto along unit direction wi (a light at infinity): unbounded.
  [[gnu::always_inline]] void spawnAlong(Ray& r, const Vec3f& wi, float time,
                                         uint32_t origin) const {
    r.o = dot(wi, ng_) < 0 ? back_ : front_;
    r.d = wi;
    r.tMin = 0;
    r.tMax = kInfinity;
    r.time = time;
    r.origin = origin;
  }

 private:
  Vec3f ng_, from_, front_, back_;
};

inline Ray spawnRay(const ShadingPoint& sp, const Vec3f& dir, float time) {
  Ray r;
  spawnRayInto(r, sp, false, dir, time);
  return r;
}
inline Ray spawnRayTo(const ShadingPoint& sp, const Vec3f& target, float time) {
  Ray r;
  spawnRayInto(r, sp, true, target, time);
  return r;
}

inline Ray spawnShadowRay(const ShadingPoint& sp, bool toPoint, const Vec3f& v, float time,
                          size_t light) {
  Ray r;
  spawnShadowRayInto(r, sp, toPoint, v, time, light);
  return r;
}

}  // namespace glint
