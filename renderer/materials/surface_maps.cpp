#include <algorithm>

#include "materials/surface.h"

namespace glint {

void splitMetal(const SurfaceMaps& maps, const ShadingPoint& sp, SurfacePoint& at) {
  const Rgb texel = maps.metallicRoughness->data(
      imageFootprint(sp, at.wo, at.footprint, maps.metallicRoughnessUv));
  // Clamped as the factors are: an HDR or out-of-range texel still gives a blend.
  const float m = std::clamp(maps.metallicFactor * texel.b, 0.0f, 1.0f);
  const float r = std::clamp(maps.roughnessFactor * texel.g, 0.0f, 1.0f);
  const Rgb base = at.kd;
  at.kd = base * (1 - m);
  at.ks = at.ks * (1 - m) + base * m;
  at.km = base * m;
  at.exponent = blinnPhongExponent(r);
  at.gloss = r;
}

float ambientOcclusion(const SurfaceMaps& maps, const ShadingPoint& sp, const SurfacePoint& at) {
  if (!maps.occlusion) return 1;
  const float occlusion =
      std::clamp(maps.occlusion->data(imageFootprint(sp, at.wo, at.footprint, maps.occlusionUv)).r,
                 0.0f, 1.0f);
  return 1 + maps.occlusionStrength * (occlusion - 1);
}

}  // namespace glint
