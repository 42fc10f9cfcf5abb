#include "render/pass_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "film/compare.h"

namespace glint {

PassPlan PassPlan::make(int spp, SamplerKind sceneSampler, const SamplingRequest& request) {
  PassPlan plan;
  plan.target = request.target;
  plan.timeLimitSeconds = request.timeLimitSeconds;
  const bool open = plan.adaptive() || plan.timeLimitSeconds > 0;
  plan.maxSpp = request.maxSpp > 0 ? request.maxSpp : spp;
  plan.minSpp = request.minSpp > 0 ? request.minSpp
                : open             ? std::min(16, plan.maxSpp)
                                   : std::min(2, plan.maxSpp);
  if (plan.minSpp > plan.maxSpp)
    throw UsageError("--min-spp " + std::to_string(plan.minSpp) +
                     " is more than the most a pixel " + "may take, " +
                     std::to_string(plan.maxSpp) + " (--max-spp, or the spp)");
  if (plan.adaptive() && plan.minSpp < 2)
    throw UsageError(
        "adaptive sampling needs --min-spp of at least 2: a pixel's error is "
        "estimated from two samples or more");
  plan.sampler = (open || request.progressive) && (sceneSampler == SamplerKind::Stratified ||
                                                   sceneSampler == SamplerKind::Regular)
                     ? SamplerKind::Sobol
                     : sceneSampler;
  for (int64_t end = plan.minSpp;; end *= 2) {
    plan.ends.push_back(static_cast<int>(std::min<int64_t>(end, plan.maxSpp)));
    if (end >= plan.maxSpp) break;
  }
  return plan;
}

FrameError estimateFrameError(const std::vector<PixelEstimate>& pixels, SamplerKind sampler) {
  FrameError e;
  if (sampler == SamplerKind::Regular || pixels.empty()) return e;
  double squared = 0, relative = 0;
  for (const PixelEstimate& p : pixels) {
    double variance[3], value[4];
    if (!p.varianceOfMean(variance)) return e;
    p.mean(value);
    for (int c = 0; c < 3; ++c) {
      squared += variance[c];
      relative += variance[c] / (value[c] * value[c] + kRelMseEpsilon);
    }
  }
  const double n = 3.0 * static_cast<double>(pixels.size());
  e.rmse = std::sqrt(squared / n);
  e.relmse = relative / n;
  return e;
}

}  // namespace glint
