#include "render/pixel_estimate.h"

#include <algorithm>
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

double ErrorTarget::ratio(const PixelEstimate& pixel) const {
  double variance[3], value[4];
  if (!pixel.varianceOfMean(variance)) return std::numeric_limits<double>::infinity();
  double worst = 0;
  if (rmse > 0) worst = (variance[0] + variance[1] + variance[2]) / 3 / (rmse * rmse);
  if (relmse > 0) {
    pixel.mean(value);
    double rel = 0;
    for (int c = 0; c < 3; ++c) rel += variance[c] / (value[c] * value[c] + kRelMseEpsilon);
    worst = std::max(worst, rel / 3 / relmse);
  }
  return worst;
}

}  // namespace glint
