#pragma once
// What a scene uses, computed once when it is loaded, and the integrator capabilities that
// follow from it (Cycles' kernel/features.h is the model). Downstream stages read it and leave
// out what the scene does not need; `glint render --stats` lists both sides.
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
  bool emission = false;    // some surface emits (k_e, or a visible area light)
  bool ambient = false;
  bool transparentShadows = false;  // asked for and some dielectric can cast them

  std::vector<std::string> used() const;
  std::vector<std::string> leftOut() const;
};

class Scene;
Features computeFeatures(const Scene& scene);

// The production kernel (integrator/batched_kernel.h) is compiled once per combination of these
// capabilities, and a render runs the instantiation that has exactly the ones its scene uses:
// a plain Phong scene carries no interior list, draws no light, lens or time samples and tests
// no branch for them. `kAll` is the general path (`glint render --no-specialize`); every
// instantiation gives the same bytes as it for the scenes it accepts
// (tests/render/specialization_test.cpp).
namespace cap {
inline constexpr unsigned kDielectrics =
    1u << 0;  // refraction, nested media, Beer, see-through shadows
inline constexpr unsigned kAreaLights = 1u << 1;     // lights averaged over several samples
inline constexpr unsigned kGloss = 1u << 2;          // glossy reflection, blurred translucency
inline constexpr unsigned kCameraSamples = 1u << 3;  // lens or shutter-time dimensions
inline constexpr unsigned kAovs = 1u << 4;           // AOV records of the camera hit
inline constexpr unsigned kCount = 5;
inline constexpr unsigned kAll = (1u << kCount) - 1;
}  // namespace cap

// The capabilities a scene needs; `aovs` when AOVs were asked for.
unsigned kernelCaps(const Features& features, bool aovs);
// "general" for kAll, "plain" for none, else the capability names joined by '+'.
std::string kernelName(unsigned caps);

}  // namespace glint
