#pragma once
// Lights of seed 000 §4.5 and §13.4.2: point and directional lights, and parallelogram (quad)
// and disk area lights. Area lights emit in one of two modes (docs/effects.md):
//  - Seed (default): the average of point lights spread over the area, each with the light's
//    intensity and falloff rule, so a shrinking light converges to the point light.
//  - Radiance ("emission": "radiance"): a one-sided emitter of radiance `intensity`, with the
//    cosine at the light and inverse-square distance, so lit surfaces show k_d × irradiance.
// Area lights are not visible to camera rays; they light surfaces only.
#include <variant>

#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

enum class Falloff { None, InverseSquare };
enum class Emission { Seed, Radiance };

struct PointLight {
  Vec3f position;
  Rgb intensity{1, 1, 1};
  Falloff falloff = Falloff::None;
};

struct DirectionalLight {
  Vec3f direction;  // unit, the direction light travels
  Rgb intensity{1, 1, 1};
};

struct QuadLight {
  Vec3f corner, edge1, edge2;  // emits towards edge1 × edge2 in radiance mode
  Rgb intensity{1, 1, 1};
  int samples = 1;
  Falloff falloff = Falloff::None;
  Emission emission = Emission::Seed;
};

struct DiskLight {
  Vec3f center, normal;  // normal unit, the side that emits in radiance mode
  float radius = 1;
  Rgb intensity{1, 1, 1};
  int samples = 1;
  Falloff falloff = Falloff::None;
  Emission emission = Emission::Seed;
};

using Light = std::variant<PointLight, DirectionalLight, QuadLight, DiskLight>;

// What one light sample delivers at a point: direction to it, where the shadow ray must reach,
// and the intensity arriving there (falloff and, in radiance mode, the geometry term applied).
struct LightSample {
  Vec3f wi;      // unit, from the point towards the light
  Vec3f target;  // the sampled point on the light (unused for directional lights)
  bool atInfinity = false;
  Rgb intensity;
};

// Shadow samples per camera sample: 1 for delta lights (nothing to sample).
int lightSampleCount(const Light& light);
// `u` in [0, 1)² picks the point on an area light; ignored by delta lights.
LightSample sampleLight(const Light& light, const Vec3f& p, Vec2f u);

}  // namespace glint
