#pragma once
// Rays traced, by kind. Each tile keeps its own and the scheduler sums them in tile order, so the
// totals are exact and independent of threading.
#include <cstdint>

namespace glint {

struct RayCounters {
  uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0;
  uint64_t nonfiniteSamples = 0;

  uint64_t total() const { return camera + shadow + reflection + refraction; }
  RayCounters& operator+=(const RayCounters& o) {
    camera += o.camera;
    shadow += o.shadow;
    reflection += o.reflection;
    refraction += o.refraction;
    nonfiniteSamples += o.nonfiniteSamples;
    return *this;
  }
};

}  // namespace glint
