#pragma once
// Lights of seed 000 §4.5 and §13.4.2: point and directional lights, and parallelogram (quad)
// and disk area lights. Area lights emit in one of two modes (docs/effects.md):
//  - Seed (default): the average of point lights spread over the area, each with the light's
//    intensity and falloff rule, so a shrinking light converges to the point light.
//  - Radiance ("emission": "radiance"): a one-sided emitter of radiance `intensity`, with the
//    cosine at the light and inverse-square distance, so lit surfaces show k_d × irradiance.
// An area light with "visible": true is also a surface of the scene that camera, reflected and
// refracted rays see (the loader adds it, with the radiance emittedRadiance gives); otherwise
// area lights only light surfaces. The environment (lights/environment.h) is a light at
// infinity that rays leaving the scene see.
#include <algorithm>
#include <cmath>
#include <variant>

#include "core/rgb.h"
#include "core/sampling.h"
#include "core/vec.h"
#include "lights/environment.h"

namespace glint {

enum class Falloff { None, InverseSquare };
enum class Emission { Seed, Radiance };

struct PointLight {
  PointLight() = default;
  PointLight(const Vec3f& p, const Rgb& i, Falloff f) : position(p), intensity(i), falloff(f) {}

  Vec3f position;
  Rgb intensity{1, 1, 1};
  Falloff falloff = Falloff::None;
  // A spot light (a scene's "spot", KHR_lights_punctual's spot) is a point light that shines
  // only within `outer` of its axis: fully within `inner`, fading in between as glTF does, by
  // the square of a linear ramp in the cosine. A point light's cone is the whole sphere.
  Vec3f spotAxis;  // unit, the way its light travels
  float cosInner = -1, cosOuter = -1;

  // A spot's outer angle is at most 90°: one comparison per point-light sample (what it costs:
  // docs/performance.md, "Leaving out what a scene does not need").
  bool isSpot() const { return cosOuter > -1; }
  // The fraction of its intensity a spot light sends towards a point in direction -wi (wi:
  // unit, from the point towards the light).
  float coneFactor(const Vec3f& wi) const {
    const float c = -dot(spotAxis, wi);
    if (!(cosInner > cosOuter)) return c >= cosOuter ? 1.0f : 0.0f;  // a hard-edged cone
    const float t = std::clamp((c - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f);
    return t * t;
  }
};

struct DirectionalLight {
  Vec3f direction;  // unit, the direction light travels
  Rgb intensity{1, 1, 1};
};

// How an area light emits. Its shape is fixed at construction, where what every sample would
// otherwise recompute from it (unit normal, area, the disk's tangent frame) is derived once.
struct AreaEmission {
  Rgb intensity{1, 1, 1};
  int samples = 1;
  Falloff falloff = Falloff::None;
  Emission emission = Emission::Seed;
  bool visible = false;

  // The radiance the light's surface shows when visible. In radiance mode, `intensity` on the
  // emitting side (and black behind). In seed mode, intensity / area on both sides: the
  // radiance of a flat emitter of that area whose intensity along its normal is `intensity`,
  // so that, seen from far enough along its axis, it lights a surface as the point lights it
  // stands for do (at distance 1 when they do not fall off).
  Rgb emittedRadiance(float area) const {
    return emission == Emission::Radiance ? intensity : intensity * (1.0f / area);
  }
};

// A parallelogram; emits towards edge1 × edge2 in radiance mode. The edges must span a
// parallelogram (the loader checks).
class QuadLight : public AreaEmission {
 public:
  QuadLight(const Vec3f& corner, const Vec3f& edge1, const Vec3f& edge2);
  const Vec3f& corner() const { return corner_; }
  const Vec3f& edge1() const { return edge1_; }
  const Vec3f& edge2() const { return edge2_; }
  const Vec3f& normal() const { return normal_; }  // unit
  float area() const { return area_; }

 private:
  Vec3f corner_, edge1_, edge2_, normal_;
  float area_;
};

// A disk; `normal` (unit) is the side that emits in radiance mode.
class DiskLight : public AreaEmission {
 public:
  DiskLight(const Vec3f& center, const Vec3f& normal, float radius);
  const Vec3f& center() const { return center_; }
  const Vec3f& normal() const { return normal_; }
  float radius() const { return radius_; }
  float area() const { return area_; }
  // Orthogonal in-plane axes of length `radius`: a point of the unit disk maps to
  // center + x·axisX + y·axisY.
  const Vec3f& axisX() const { return axisX_; }
  const Vec3f& axisY() const { return axisY_; }

 private:
  Vec3f center_, normal_, axisX_, axisY_;
  float radius_, area_;
};

using Light = std::variant<PointLight, DirectionalLight, QuadLight, DiskLight, EnvironmentLight>;

// What one light sample delivers at a point: direction to it, where the shadow ray must reach,
// and the intensity arriving there (falloff and, in radiance mode, the geometry term applied).
struct LightSample {
  Rgb intensity;
  Vec3f wi;      // unit, from the point towards the light
  Vec3f target;  // the sampled point on the light (unused for directional lights)
  bool atInfinity = false;
};

// A delta light (point or directional): one shadow ray, and no sample drawn on it.
inline bool isDeltaLight(const Light& light) {
  return std::holds_alternative<PointLight>(light) ||
         std::holds_alternative<DirectionalLight>(light);
}

// Shadow samples per camera sample: 1 for delta lights (nothing to sample).
int lightSampleCount(const Light& light);

// A light's share of a shading point: the mean of what its `count` samples let through, `sum`
// their total (seed 000 §13.4.2: an area light is the average of point lights over its area).
inline Rgb meanOverSamples(const Rgb& sum, int count) {
  return count == 1 ? sum : sum * (1.0f / static_cast<float>(count));
}

// The sample of a light at point y on it (the lighting parameters and, in radiance mode, the
// light's unit normal and area), seen from p.
[[gnu::always_inline]] inline LightSample lightSampleFrom(const Vec3f& p, const Vec3f& y,
                                                          const Rgb& intensity, Falloff falloff,
                                                          Emission emission,
                                                          const Vec3f& lightNormal, float area) {
  const Vec3f toLight = y - p;
  // One square root and one division serve the direction and the inverse square.
  const float invDist = 1.0f / std::sqrt(dot(toLight, toLight));
  const float invDist2 = invDist * invDist;
  LightSample s;
  s.wi = toLight * invDist;
  s.target = y;
  if (emission == Emission::Radiance) {
    // E = ∫ L cosθ_y / r² dA estimated with one uniform point: L·max(0, cosθ_y)·A / r².
    const float cosY = std::max(0.0f, -dot(lightNormal, s.wi));
    s.intensity = intensity * (cosY * area * invDist2);
  } else {
    s.intensity = falloff == Falloff::InverseSquare ? intensity * invDist2 : intensity;
  }
  return s;
}

// The sample of each type of light, seen from p: sampleLight's (below), for callers that look a
// light's type up once for many samples. u in [0, 1)² picks the point on an area light or the
// direction of the environment, which a uniform sky draws about n, the point's unit shading
// normal; delta lights ignore both. An environment's sample arrives from infinity with
// radiance / pdf as its intensity: times k_d·cos θ it estimates k_d × E, E = ∫ L cos θ dω, as a
// radiance-mode area light's does.
[[gnu::always_inline]] inline LightSample sampleLight(const PointLight& pl, const Vec3f& p,
                                                      const Vec3f&, Vec2f) {
  LightSample s = lightSampleFrom(p, pl.position, pl.intensity, pl.falloff, Emission::Seed, {}, 0);
  if (pl.isSpot()) [[unlikely]]
    s.intensity = s.intensity * pl.coneFactor(s.wi);
  return s;
}
[[gnu::always_inline]] inline LightSample sampleLight(const QuadLight& q, const Vec3f& p,
                                                      const Vec3f&, Vec2f u) {
  return lightSampleFrom(p, q.corner() + u.x * q.edge1() + u.y * q.edge2(), q.intensity, q.falloff,
                         q.emission, q.normal(), q.area());
}
[[gnu::always_inline]] inline LightSample sampleLight(const DiskLight& d, const Vec3f& p,
                                                      const Vec3f&, Vec2f u) {
  const Vec2f disk = squareToDiskConcentric(u);
  return lightSampleFrom(p, d.center() + disk.x * d.axisX() + disk.y * d.axisY(), d.intensity,
                         d.falloff, d.emission, d.normal(), d.area());
}
[[gnu::always_inline]] inline LightSample sampleLight(const DirectionalLight& dl, const Vec3f& p,
                                                      const Vec3f&, Vec2f) {
  LightSample s;
  s.atInfinity = true;
  s.wi = -dl.direction;
  s.intensity = dl.intensity;
  s.target = p + s.wi;
  return s;
}
[[gnu::always_inline]] inline LightSample sampleLight(const EnvironmentLight& env, const Vec3f& p,
                                                      const Vec3f& n, Vec2f u) {
  LightSample s;
  s.atInfinity = true;
  const EnvironmentSample e = env.sample(n, u);
  s.wi = e.wi;
  s.intensity = e.radianceOverPdf;
  s.target = p + s.wi;
  return s;
}

// The sample of any light (the typed forms above). Inline: out of line, every sample came back
// through memory, a 40-byte struct stored field by field and loaded in 16-byte moves, which
// stalls the load (store forwarding).
[[gnu::always_inline]] inline LightSample sampleLight(const Light& light, const Vec3f& p,
                                                      const Vec3f& n, Vec2f u) {
  if (const auto* pl = std::get_if<PointLight>(&light)) return sampleLight(*pl, p, n, u);
  if (const auto* q = std::get_if<QuadLight>(&light)) return sampleLight(*q, p, n, u);
  if (const auto* d = std::get_if<DiskLight>(&light)) return sampleLight(*d, p, n, u);
  // The environment last: a directional light's sample makes no more tests than before it was
  // added (each is paid per point and light).
  if (const auto* dl = std::get_if<DirectionalLight>(&light)) [[likely]]
    return sampleLight(*dl, p, n, u);
  return sampleLight(std::get<EnvironmentLight>(light), p, n, u);
}

}  // namespace glint
