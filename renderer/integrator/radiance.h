#pragma once
// What both integrators (reference.h, batched_kernel.h) return for a camera sample, and the one
// rule they share for where a branch of the ray tree stops.
#include <cstdint>

#include "core/rgb.h"

namespace glint {

// A branch whose share (branchShare) falls below this in every channel is not traced. Where no
// hit on its path sends on more light than reaches it, it could change its pixel by at most
// this much times the radiance behind it (docs/shading.md).
inline constexpr float kDefaultMinThroughput = 1.0f / 1024.0f;

// A branch's share of its sample: the product of the weights along its path, each divided by
// the gain of the hit that sent it where that gain is above 1 (materials' coherentGain). A
// hit's branches then share at most what reached it, in each channel, so no depth of the tree
// holds 3/minThroughput branches above the cutoff, and a sample's rays grow with its max_depth
// rather than exponentially. The product of the weights alone never falls where a material
// gains (a dielectric with a surface mirror k_m, or constant k_m + k_t above 1): nested glass of
// k_m 1 multiplied its rays at every depth. Where no hit gains, the share is that product, the
// branch's weight in its pixel.
inline Rgb branchShare(const Rgb& parentShare, const Rgb& weight, float gain) {
  return gain > 1 ? parentShare * weight * (1 / gain) : parentShare * weight;
}

struct Radiance {
  Rgb L;
  float alpha = 0;    // 1 when the camera ray hit geometry
  bool valid = true;  // false for a non-finite sample, which the film counts as black
  // The rays the sample traced, its camera ray included: what it cost, which adaptive sampling
  // weighs against its noise (render/pixel_estimate.h). Both integrators count the same rays.
  uint64_t rays = 0;
};

}  // namespace glint
