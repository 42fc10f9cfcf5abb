#include "lights/light.h"

namespace glint {

LightSample sampleLight(const Light& light, const Vec3f& p) {
  if (const auto* pl = std::get_if<PointLight>(&light)) {
    const Vec3f toLight = pl->position - p;
    const float dist2 = dot(toLight, toLight);
    LightSample s;
    s.wi = toLight / std::sqrt(dist2);
    s.target = pl->position;
    s.intensity =
        pl->falloff == Falloff::InverseSquare ? pl->intensity * (1.0f / dist2) : pl->intensity;
    return s;
  }
  const auto& dl = std::get<DirectionalLight>(light);
  LightSample s;
  s.wi = -dl.direction;
  s.target = p + s.wi;  // unused: directional shadow rays run to infinity
  s.atInfinity = true;
  s.intensity = dl.intensity;
  return s;
}

}  // namespace glint
