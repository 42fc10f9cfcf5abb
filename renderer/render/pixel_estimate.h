#pragma once
// What a render keeps of each pixel between passes: for each of its two independently sampled
// halves (core/sampler.h), the running mean of its samples, their summed coverage and the rays
// they traced. From them come the pixel's mean, an unbiased estimate of that mean's variance
// that stays valid under stratification (the halves' difference, docs/validation.md, Error
// estimate) and what a sample of the pixel costs. Samples are added in index order within a
// half, so the state is the same bits whatever the passes, threads or tiles that added them.
#include <cstdint>
#include <span>
#include <vector>

#include "core/unwritten_allocator.h"
#include "integrator/radiance.h"

namespace glint {

struct HalfEstimate {
  double mean[3] = {0, 0, 0};  // a running mean (not a sum: no loss of small late samples)
  double alpha = 0;            // summed coverage
  uint64_t rays = 0;           // summed Radiance::rays
  int32_t count = 0;

  void add(const Rgb& L, double coverage, uint64_t traced) {
    ++count;
    rays += traced;
    const double inv = 1.0 / count;
    mean[0] += (double(L.r) - mean[0]) * inv;
    mean[1] += (double(L.g) - mean[1]) * inv;
    mean[2] += (double(L.b) - mean[2]) * inv;
    alpha += coverage;
  }
};

struct PixelEstimate {
  HalfEstimate half[2];

  int64_t samples() const { return int64_t{half[0].count} + half[1].count; }
  // What a sample costs: the rays it traced on average, at least its camera ray (1 with no
  // samples).
  double raysPerSample() const;

  // The pixel's RGBA: the mean of all its samples.
  void mean(double out[4]) const;

  // The variance of each channel of mean(), estimated from the difference of the halves'
  // means: for independent halves of n0 and n1 samples, E[(m0 − m1)²]·n0·n1/n² is the variance
  // of the pooled mean (exactly so for equal halves, whatever the sampler does inside each).
  // One degree of freedom per channel: unbiased, noisy for one pixel. False when a half is
  // empty (one sample).
  bool varianceOfMean(double out[3]) const;
};

// The states of a frame's pixels. Made with a size, its elements are unwritten: the render
// session writes them on the render's threads (initialiseInBlocks) before any is read.
using PixelEstimates = std::vector<PixelEstimate, UnwrittenAllocator<PixelEstimate>>;

// A pixel's estimated squared error, as `glint compare` averages it over channels: its mean's
// variance (MSE), and that over value² + kRelMseEpsilon (relMSE). False where the pixel has no
// estimate (PixelEstimate::varianceOfMean).
struct PixelError {
  double mse = 0, relmse = 0;
  static bool of(const PixelEstimate& pixel, PixelError& out);

  // The error a pixel's mean keeps when an edge crosses it, which the halves cannot see: each
  // half's stratified samples fall on either side in nearly fixed proportions, so the halves
  // often agree and read zero (whitted at uniform's 128-spp error took 2.7x uniform's samples).
  // A straight edge of contrast C crossing a pixel whose halves each stratify n/2 samples
  // (jittered, or an Owen-scrambled net) passes through about 1.2·√(n/2) strata of each, and
  // each adds a one-sample variance of C²/6 on average (at most C²/4) in (n/2)² to its half's
  // mean: the pooled mean's variance is about 0.28·C²/n^{3/2}, and 2√2·C²/(4·n^{3/2}) for the
  // worst-placed edge. The floor is C²/(4·n^{3/2}), the typical case. `contrast` is, per
  // channel, the largest difference between the pixel's mean and a 4-neighbour's, the least
  // contrast an edge there can have.
  static PixelError edgeFloor(const PixelEstimate& pixel, const double contrast[3]);
};

// How much one sample of the frame spreads, pixel to pixel: the root mean square over a set of
// pixels (the probes of PassPlan) of each pixel's per-sample deviation σ = √(samples · MSE) (and
// the same of relMSE) times the square root of its cost c (rays a sample). It turns a target for
// the frame into each pixel's share (ErrorTarget::ratio).
struct FrameSpread {
  double deviation = 0, relativeDeviation = 0;
  static FrameSpread of(const std::vector<PixelEstimate>& probes);
  bool operator==(const FrameSpread&) const = default;
};

// What adaptive sampling aims at: the frame's RMSE or relMSE, as `glint compare` measures it.
struct ErrorTarget {
  double rmse = 0, relmse = 0;  // 0: no target of that kind
  bool any() const { return rmse > 0 || relmse > 0; }
  bool operator==(const ErrorTarget&) const = default;
  // How far a pixel is from its share of the target, at most 1 where it meets it; the larger of
  // the two targets given; infinity where the pixel has no estimate. The frame's squared error
  // falls fastest per ray traced when each pixel's samples grow with its per-sample deviation σ
  // over the square root of its cost c (Neyman's allocation with costs: minimising Σ c·n under
  // Σ σ²/n fixed gives n ∝ σ/√c), that is when a pixel of n samples stops at
  // σ / (n·√c) ≤ E² / s, s being the frame's spread: then its squared error is E²·σ√c/s, and the
  // frame's mean of them is at most E² (the mean of σ√c is at most their root mean square s).
  // The ratio is σ / (n·√c) · s / E². Without the cost, the pixels that stop first are the cheap
  // ones and a sample of those left costs more, so samples saved turned into far fewer rays
  // saved (docs/validation.md, "Adaptive sampling against uniform sampling").
  double ratio(const PixelEstimate& pixel, const FrameSpread& spread) const;
  // The same for an error of a pixel of `samples` samples of `raysPerSample` rays each
  // (infinity for none).
  double ratio(const PixelError& error, int64_t samples, double raysPerSample,
               const FrameSpread& spread) const;
};
}  // namespace glint
