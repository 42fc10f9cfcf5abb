#pragma once
// The set of capabilities a scene needs, computed once at build time. Downstream stages read it
// and leave out what the scene does not need; `glint render --stats` lists both sides.
#include <string>
#include <vector>

namespace glint {

struct Features {
  bool instancing = false;
  bool planes = false;
  bool pointLights = false;
  bool directionalLights = false;
  bool areaLights = false;
  bool depthOfField = false;
  bool motion = false;  // some object has keys (time steps for Embree, a time sample)
  bool gloss = false;   // glossy reflection or blurred translucency
  bool shadows = false;
  bool specular = false;    // some Phong material has ks ≠ 0
  bool reflection = false;  // some material has km ≠ 0
  bool refraction = false;  // some dielectric
  bool absorption = false;  // some dielectric with attenuation ≠ 1
  bool textures = false;    // some checker
  bool ambient = false;
  bool transparentShadows = false;  // asked for and some dielectric can cast them

  std::vector<std::string> used() const;
  std::vector<std::string> leftOut() const;
};

class Scene;
Features computeFeatures(const Scene& scene);

}  // namespace glint
