#pragma once
// How a render spends its samples: in passes that double each pixel's samples, from the first
// pass's to the most a pixel may take, every pixel that still needs samples taking part in each
// (docs/output.md, Passes and adaptive sampling). What a pass does depends only on the state
// the passes before it left, never on time or threads, except where a time limit stops it.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/sampler.h"
#include "integrator/footprint.h"
#include "render/pixel_estimate.h"

namespace glint {

// What the user asked for beyond the scene's spp (`glint render --target-rmse ...`).
struct SamplingRequest {
  ErrorTarget target;
  int minSpp = 0, maxSpp = 0;   // 0: the defaults below
  double timeLimitSeconds = 0;  // 0: none
  bool progressive = false;     // to be continued to more samples later (--resumable)
};

// The first pass of every render unless --min-spp says otherwise. Every pixel takes it, so it
// bounds what adaptive sampling can save (depth_of_field at uniform's 32-spp error: at most
// 1.38x the rays after 16 samples, 1.64x after 8, tools/adaptive-oracle.py). 8 saves more rays
// than 16 on nearly every scene and level (docs/validation.md, "Adaptive sampling against
// uniform sampling"); the choices keep each pixel's ratios from pass to pass (ChoiceCache), so
// the extra pass costs even the fastest frames less than it saves. In a plain render, the passes
// to 2 and 4 revisited every pixel for one sample a half, an overhead that outweighs, on a cheap
// frame, their early points of error against time (docs/performance.md, "What passes cost").
inline constexpr int kDefaultFirstPassSpp = 8;

// What PassPlan::choosePixels keeps from one choice to the next: each pixel's ratios (by its
// halves, by its edge floor), its mean, and the samples it had when they were taken, for one
// target, spread and frame. A pass changes a pixel only by adding samples, so a choice recomputes
// them only where the sample count moved (and the edge ratios of those pixels' 4-neighbours):
// taken anew over the whole frame at every pass, each short pass paid for the whole frame's.
// Its arrays are first written on the render's threads (ChoiceCache::reset).
struct ChoiceCache {
  std::vector<double, UnwrittenAllocator<double>> ratio, edgeRatio, means;
  std::vector<int64_t, UnwrittenAllocator<int64_t>> samples;  // -1 where not taken yet
  ErrorTarget target;
  FrameSpread spread;
  int width = 0;
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

  // Passes from --min-spp (default min(kDefaultFirstPassSpp, max)), doubling up to --max-spp
  // (default spp; without a target or a time limit, the spp itself). Throws UsageError for
  // bounds that contradict each other.
  static PassPlan make(int spp, SamplerKind sceneSampler, const SamplingRequest& request);
  bool adaptive() const { return target.any(); }
  // What the render will do, for its announcement: "at 16 spp", "for at most 3 s, up to 4096
  // spp (a first pass of 8 spp always finishes)", "until the estimated RMSE is at most 0.01,
  // 8 to 4096 spp per pixel".
  std::string describe() const;
  // Whether the sets are the same whatever the total: Sobol's and random's are, so a render
  // can be continued to any spp; a stratified set is laid out for maxSpp.
  bool progressive() const {
    return sampler == SamplerKind::Sobol || sampler == SamplerKind::Random;
  }
  // The samples each pixel's texture footprint is shared among (integrator/footprint.h): the
  // total where the sets are laid out for it; for a progressive render the most there can be,
  // since it may stop or be continued at any spp, and a sample must filter alike in all of
  // them (a resumed render filtered its first samples for their spp and wrote other pixels
  // than a straight one on a textured scene).
  int footprintSpp() const { return progressive() ? kFinestFootprintSpp : maxSpp; }

  // Marks in `sampled` the pixels of a `width`-wide row-major grid that take part in the pass
  // that ends at `end` samples, and returns how many: those below `end` that, under adaptive
  // sampling, have fewer than minSpp samples, or where a pixel of their 3 × 3 neighbourhood
  // (themselves included) is above its share of the target (ErrorTarget::ratio, with the
  // frame's `spread`), or that are above it by the edge floor their 4-neighbours' means set
  // (PixelError::edgeFloor). One pixel's estimate has a degree of freedom per channel, and a
  // pixel on an edge often reads zero when both halves saw the same side of it; its neighbours
  // on the same edge rarely all do, so the neighbourhood's worst keeps the edge sampling (with
  // its mean instead, whitted's frame missed a target of 0.002 at 0.00201). Where they do (a
  // checker of 2-pixel squares seen face on), the floor keeps it: without it whitted and csg
  // lost to uniform sampling at low errors (docs/validation.md, "Adaptive sampling against
  // uniform sampling"). Every input lies within one pixel.
  // `kept` carries each pixel's inputs from one choice to the next (ChoiceCache).
  int64_t choosePixels(std::span<const PixelEstimate> pixels, int width, int end,
                       const FrameSpread& spread, ChoiceCache& kept,
                       std::vector<uint8_t>& sampled) const;
  // How far a pixel's samples depend on other pixels': one pixel per adaptive decision, one
  // fewer than the passes. A crop renders this many pixels around it (inside the frame) so
  // that each of its pixels is sampled as in the full frame.
  int apron() const { return adaptive() ? static_cast<int>(ends.size()) : 0; }

 private:
  // Brings `kept` up to date with `pixels` and `spread` (ChoiceCache).
  void refreshRatios(std::span<const PixelEstimate> pixels, int width, int height,
                     const FrameSpread& spread, ChoiceCache& kept) const;
};

// The pixels whose first pass measures the frame's spread (FrameSpread) for adaptive sampling:
// every stride-th pixel of the full frame in both axes, from `offset`, whatever the crop, so
// that a crop's pixels get the same shares of the target as the full frame's. The stride aims
// at kProbesWanted probes, at most one pixel in kMaxStride² (a 1/64 of the first pass's work on
// a large frame).
struct ProbeLattice {
  static constexpr double kProbesWanted = 256;
  static constexpr int kMaxStride = 8;
  int stride = 1, offset = 0, columns = 0, rows = 0;
  static ProbeLattice of(int width, int height);
};

// A frame's estimated error: the pixels' estimates (PixelEstimate::varianceOfMean) averaged as
// `glint compare` averages squared errors. Absent when a pixel has no estimate (one sample, or
// a regular grid, which has no randomness to measure).
struct FrameError {
  std::optional<double> rmse, relmse;
};
FrameError estimateFrameError(std::span<const PixelEstimate> pixels, SamplerKind sampler);

// The frame's estimated error (estimateFrameError) and the fewest, most and total samples of
// its pixels, in one read of them.
struct FrameSummary {
  FrameError error;
  int64_t fewestSamples = 0, mostSamples = 0, samples = 0;
};
FrameSummary summariseFrame(std::span<const PixelEstimate> pixels, SamplerKind sampler);

}  // namespace glint
