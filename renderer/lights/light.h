#pragma once
// Lights of seed 000 §4.5: point lights and directional lights. Area lights (quad, disk) are
// parsed by the loader and arrive with the distribution effects.
#include <variant>

#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

enum class Falloff { None, InverseSquare };

struct PointLight {
  Vec3f position;
  Rgb intensity{1, 1, 1};
  Falloff falloff = Falloff::None;
};

struct DirectionalLight {
  Vec3f direction;  // unit, the direction light travels
  Rgb intensity{1, 1, 1};
};

using Light = std::variant<PointLight, DirectionalLight>;

// What a light delivers at a point: direction to it, how far the shadow ray must reach, and
// the intensity arriving (falloff applied).
struct LightSample {
  Vec3f wi;      // unit, from the point towards the light
  Vec3f target;  // a point on the light, or far along wi for directional lights
  bool atInfinity = false;
  Rgb intensity;
};

LightSample sampleLight(const Light& light, const Vec3f& p);

}  // namespace glint
