#pragma once
// What a render keeps of each pixel between passes: for each of its two independently sampled
// halves (core/sampler.h), the running mean of its samples and their summed coverage. From them
// come the pixel's mean and an unbiased estimate of that mean's variance that stays valid under
// stratification: the halves' difference (docs/validation.md, Error estimate). Samples are
// added in index order within a half, so the state is the same bits whatever the passes,
// threads or tiles that added them.
#include <cstdint>

#include "integrator/radiance.h"

namespace glint {

struct HalfEstimate {
  double mean[3] = {0, 0, 0};  // a running mean (not a sum: no loss of small late samples)
  double alpha = 0;            // summed coverage
  int32_t count = 0;

  void add(const Rgb& L, double coverage) {
    ++count;
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

  // The pixel's RGBA: the mean of all its samples.
  void mean(double out[4]) const;

  // The variance of each channel of mean(), estimated from the difference of the halves'
  // means: for independent halves of n0 and n1 samples, E[(m0 − m1)²]·n0·n1/n² is the variance
  // of the pooled mean (exactly so for equal halves, whatever the sampler does inside each).
  // One degree of freedom per channel: unbiased, noisy for one pixel. False when a half is
  // empty (one sample).
  bool varianceOfMean(double out[3]) const;
};

// The per-pixel errors that adaptive sampling aims at: the RMSE (root of the channels' mean
// squared error) or the relMSE (squared error over value² + kRelMseEpsilon, as `glint compare`
// has it, channels' mean).
struct ErrorTarget {
  double rmse = 0, relmse = 0;  // 0: no target of that kind
  bool any() const { return rmse > 0 || relmse > 0; }
  // The pixel's estimated error over the target, in squared terms (MSE / rmse², relMSE /
  // relmse), the larger of the two targets given: at most 1 meets them. Infinity where the
  // pixel has no estimate.
  double ratio(const PixelEstimate& pixel) const;
};

}  // namespace glint
