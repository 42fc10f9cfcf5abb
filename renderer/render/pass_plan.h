#pragma once
// How a render spends its samples: in passes that double each pixel's samples, from the first
// pass's to the most a pixel may take, every pixel that still needs samples taking part in each
// (docs/output.md, Passes and adaptive sampling). What a pass does depends only on the state
// the passes before it left, never on time or threads, except where a time limit stops it.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/sampler.h"
#include "render/pixel_estimate.h"

namespace glint {

// What the user asked for beyond the scene's spp (`glint render --target-rmse ...`).
struct SamplingRequest {
  ErrorTarget target;
  int minSpp = 0, maxSpp = 0;   // 0: the defaults below
  double timeLimitSeconds = 0;  // 0: none
  bool progressive = false;     // to be continued to more samples later (--resumable)
};

struct PassPlan {
  // The samples per pixel at the end of each pass: doubling from the first to the last.
  std::vector<int> ends;
  int minSpp = 1, maxSpp = 1;
  ErrorTarget target;
  double timeLimitSeconds = 0;
  // The sampler actually used: an adaptive, time-limited or resumable render stops pixels at
  // sample counts no one knows in advance, so it needs sets whose every power-of-two prefix is
  // stratified; the stratified and regular samplers' sets are laid out for one total, so such
  // a render draws from the Owen-scrambled Sobol sequence instead (and says so in its
  // statistics).
  SamplerKind sampler = SamplerKind::Stratified;

  // Without a target or time limit: passes 2, 4, 8, ... up to spp; with them, from --min-spp
  // (default min(16, max)) to --max-spp (default spp). Throws UsageError for bounds that
  // contradict each other.
  static PassPlan make(int spp, SamplerKind sceneSampler, const SamplingRequest& request);
  bool adaptive() const { return target.any(); }
  // Whether the sets are the same whatever the total: Sobol's and random's are, so a render
  // can be continued to any spp; a stratified set is laid out for maxSpp.
  bool progressive() const {
    return sampler == SamplerKind::Sobol || sampler == SamplerKind::Random;
  }

  // Marks in `sampled` the pixels of a `width`-wide row-major grid that take part in the pass
  // that ends at `end` samples, and returns how many: those below `end` that, under adaptive
  // sampling, have fewer than minSpp samples, or whose error over the target
  // (ErrorTarget::ratio), or its mean over their 3 × 3 neighbourhood, is above 1. One pixel's
  // estimate has a degree of freedom per channel (with 4× the target's variance, it reads below
  // the target one time in three); the neighbourhood's nine give the decision the steadiness it
  // lacks, and the larger of the two keeps a noisy pixel among quiet ones sampling.
  int64_t choosePixels(const std::vector<PixelEstimate>& pixels, int width, int end,
                       std::vector<uint8_t>& sampled) const;
  // How far a pixel's samples depend on other pixels': one pixel per adaptive decision, one
  // fewer than the passes. A crop renders this many pixels around it (inside the frame) so
  // that each of its pixels is sampled as in the full frame.
  int apron() const { return adaptive() ? static_cast<int>(ends.size()) : 0; }
};

// A frame's estimated error: the pixels' estimates (PixelEstimate::varianceOfMean) averaged as
// `glint compare` averages squared errors. Absent when a pixel has no estimate (one sample, or
// a regular grid, which has no randomness to measure).
struct FrameError {
  std::optional<double> rmse, relmse;
};
FrameError estimateFrameError(const std::vector<PixelEstimate>& pixels, SamplerKind sampler);

}  // namespace glint
