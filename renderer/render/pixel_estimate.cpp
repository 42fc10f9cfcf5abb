#include "render/pixel_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "film/compare.h"

namespace glint {

void PixelEstimate::mean(double out[4]) const {
  const double n0 = half[0].count, n1 = half[1].count, n = n0 + n1;
  if (n == 0) {
    out[0] = out[1] = out[2] = out[3] = 0;
    return;
  }
  for (int c = 0; c < 3; ++c) out[c] = (n0 * half[0].mean[c] + n1 * half[1].mean[c]) / n;
  out[3] = (half[0].alpha + half[1].alpha) / n;
}

double PixelEstimate::raysPerSample() const {
  const int64_t n = samples();
  if (n == 0) return 1;
  return std::max(1.0, double(half[0].rays + half[1].rays) / double(n));
}

bool PixelEstimate::varianceOfMean(double out[3]) const {
  const double n0 = half[0].count, n1 = half[1].count, n = n0 + n1;
  if (n0 == 0 || n1 == 0) return false;
  const double weight = n0 * n1 / (n * n);
  for (int c = 0; c < 3; ++c) {
    const double d = half[0].mean[c] - half[1].mean[c];
    out[c] = weight * d * d;
  }
  return true;
}

bool PixelError::of(const PixelEstimate& pixel, PixelError& out) {
  double variance[3], value[4];
  if (!pixel.varianceOfMean(variance)) return false;
  pixel.mean(value);
  out = {};
  for (int c = 0; c < 3; ++c) {
    out.mse += variance[c] / 3;
    out.relmse += variance[c] / (value[c] * value[c] + kRelMseEpsilon) / 3;
  }
  return true;
}

PixelError PixelError::edgeFloor(const PixelEstimate& pixel, const double contrast[3]) {
  const double n = static_cast<double>(pixel.samples());
  PixelError out;
  if (n == 0) return out;
  double value[4];
  pixel.mean(value);
  for (int c = 0; c < 3; ++c) {
    const double variance = contrast[c] * contrast[c] / (4 * n * std::sqrt(n));
    out.mse += variance / 3;
    out.relmse += variance / (value[c] * value[c] + kRelMseEpsilon) / 3;
  }
  return out;
}

FrameSpread FrameSpread::of(const std::vector<PixelEstimate>& probes) {
  double squared = 0, relative = 0;
  int64_t count = 0;
  for (const PixelEstimate& p : probes) {
    PixelError e;
    if (!PixelError::of(p, e)) continue;
    const double n = static_cast<double>(p.samples()), cost = p.raysPerSample();
    squared += n * e.mse * cost;
    relative += n * e.relmse * cost;
    ++count;
  }
  if (count == 0) return {};
  return {std::sqrt(squared / double(count)), std::sqrt(relative / double(count))};
}

double ErrorTarget::ratio(const PixelEstimate& pixel, const FrameSpread& spread) const {
  PixelError e;
  if (!PixelError::of(pixel, e)) return std::numeric_limits<double>::infinity();
  return ratio(e, pixel.samples(), pixel.raysPerSample(), spread);
}

double ErrorTarget::ratio(const PixelError& e, int64_t samples, double raysPerSample,
                          const FrameSpread& spread) const {
  if (samples <= 0) return std::numeric_limits<double>::infinity();
  // sqrt(squared error / (n·c)) is the pixel's per-sample deviation over n·√c.
  const double nc = static_cast<double>(samples) * raysPerSample;
  double worst = 0;
  if (rmse > 0) worst = std::sqrt(e.mse / nc) * spread.deviation / (rmse * rmse);
  if (relmse > 0)
    worst = std::max(worst, std::sqrt(e.relmse / nc) * spread.relativeDeviation / relmse);
  return worst;
}

}  // namespace glint
