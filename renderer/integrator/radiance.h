#pragma once
// What both integrators (reference.h, batched_kernel.h) return for a camera sample, and the one
// rule they share for where a branch of the ray tree stops.
#include <cstdint>

#include "core/rgb.h"

namespace glint {

// A branch whose throughput (the product of the weights along its path) falls below this in
// every channel is not traced: it could change its pixel by at most this much times the
// radiance behind it (docs/shading.md).
inline constexpr float kDefaultMinThroughput = 1.0f / 1024.0f;

struct Radiance {
  Rgb L;
  float alpha = 0;    // 1 when the camera ray hit geometry
  bool valid = true;  // false for a non-finite sample, which the film counts as black
  // The rays the sample traced, its camera ray included: what it cost, which adaptive sampling
  // weighs against its noise (render/pixel_estimate.h). Both integrators count the same rays.
  uint64_t rays = 0;
};

}  // namespace glint
