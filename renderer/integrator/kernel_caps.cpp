#include "integrator/kernel_caps.h"

#include "scene/features.h"

namespace glint {

unsigned kernelCaps(const Features& f, bool aovs) {
  unsigned c = 0;
  if (f.refraction) c |= cap::kDielectrics;
  if (f.areaLights) c |= cap::kAreaLights;
  if (f.gloss) c |= cap::kGloss;
  if (f.depthOfField || f.motion) c |= cap::kCameraSamples;
  if (aovs) c |= cap::kAovs;
  return c;
}

std::string kernelName(unsigned caps) {
  if (caps == cap::kAll) return "general";
  if (caps == 0) return "plain";
  static const char* const names[cap::kCount] = {"dielectrics", "area_lights", "gloss",
                                                 "camera_samples", "aovs"};
  std::string out;
  for (unsigned i = 0; i < cap::kCount; ++i)
    if (caps & (1u << i)) out += (out.empty() ? "" : "+") + std::string(names[i]);
  return out;
}

}  // namespace glint
