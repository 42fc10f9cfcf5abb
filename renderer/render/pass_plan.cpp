#include "render/pass_plan.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>

#include "core/error.h"
#include "render/tile_scheduler.h"

namespace glint {

PassPlan PassPlan::make(int spp, SamplerKind sceneSampler, const SamplingRequest& request) {
  PassPlan plan;
  plan.target = request.target;
  plan.timeLimitSeconds = request.timeLimitSeconds;
  const bool open = plan.adaptive() || plan.timeLimitSeconds > 0;
  // Without a target or a time limit every pixel takes the spp: a --max-spp apart from it
  // would silently render another count than the frame's glint:spp says.
  if (!open && request.maxSpp > 0 && request.maxSpp != spp)
    throw UsageError("--max-spp " + std::to_string(request.maxSpp) +
                     " bounds adaptive sampling or a --time-limit render; without either every "
                     "pixel takes the spp (" +
                     std::to_string(spp) + "): give --spp " + std::to_string(request.maxSpp) +
                     " instead");
  plan.maxSpp = request.maxSpp > 0 ? request.maxSpp : spp;
  plan.minSpp = request.minSpp > 0 ? request.minSpp : std::min(kDefaultFirstPassSpp, plan.maxSpp);
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

std::string PassPlan::describe() const {
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  const bool timed = timeLimitSeconds > 0;
  if (!adaptive() && !timed) return "at " + std::to_string(maxSpp) + " spp";
  std::string s;
  if (adaptive()) {
    s = "until the estimated ";
    if (target.rmse > 0) s += "RMSE is at most " + number(target.rmse);
    if (target.rmse > 0 && target.relmse > 0) s += " and the ";
    if (target.relmse > 0) s += "relMSE is at most " + number(target.relmse);
    s += ", " + std::to_string(minSpp) + " to " + std::to_string(maxSpp) + " spp per pixel";
    if (timed) s += ", ";
  }
  if (timed)
    s += "for at most " + number(timeLimitSeconds) + " s" +
         (adaptive() ? std::string()
                     : ", up to " + std::to_string(maxSpp) + " spp (a first pass of " +
                           std::to_string(minSpp) + " spp always finishes)");
  return s;
}

// The loops below run on the threads of the caller's arena (the render's, withThreads): each
// pixel's result depends on its inputs alone, and the sums are of integers or split the same
// way for any thread count, so the choices and statistics do not depend on the threads. Run on
// one thread, they would be a serial step between passes that every other thread waits out.

int64_t PassPlan::choosePixels(std::span<const PixelEstimate> pixels, int width, int end,
                               const FrameSpread& spread, ChoiceCache& kept,
                               std::vector<uint8_t>& sampled) const {
  sampled.resize(pixels.size());  // every entry is written below
  const int height = width > 0 ? static_cast<int>(pixels.size() / size_t(width)) : 0;
  // A ratio is read only where a pixel has its first pass and is below this one's end.
  if (adaptive() && end > minSpp) refreshRatios(pixels, width, height, spread, kept);
  const auto chooseRow = [&](int y) {
    int64_t count = 0;
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * size_t(width) + size_t(x);
      const int64_t n = pixels[p].samples();
      bool needs = n < end;
      if (needs && adaptive() && n >= minSpp) {
        double worst = 0;
        for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny)
          for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx)
            worst = std::max(worst, kept.ratio[size_t(ny) * size_t(width) + size_t(nx)]);
        needs = std::max(worst, kept.edgeRatio[p]) > 1;
      }
      sampled[p] = needs;
      count += needs;
    }
    return count;
  };
  std::vector<int64_t> chosen(size_t(height), 0);
  forEachRow(0, height, [&](int y) { chosen[size_t(y)] = chooseRow(y); });
  return std::accumulate(chosen.begin(), chosen.end(), int64_t{0});
}

void PassPlan::refreshRatios(std::span<const PixelEstimate> pixels, int width, int height,
                             const FrameSpread& spread, ChoiceCache& kept) const {
  const size_t size = pixels.size();
  if (kept.samples.size() != size || kept.width != width || !(kept.target == target) ||
      !(kept.spread == spread)) {
    kept.ratio.resize(size);
    kept.edgeRatio.resize(size);
    kept.means.resize(3 * size);
    kept.samples.resize(size);
    forEachBlock(size, [&](size_t begin, size_t end) {
      std::fill(kept.ratio.begin() + begin, kept.ratio.begin() + end, 0.0);
      std::fill(kept.edgeRatio.begin() + begin, kept.edgeRatio.begin() + end, 0.0);
      std::fill(kept.means.begin() + 3 * begin, kept.means.begin() + 3 * end, 0.0);
      std::fill(kept.samples.begin() + begin, kept.samples.begin() + end, int64_t{-1});
    });
    kept.target = target;
    kept.spread = spread;
    kept.width = width;
  }
  // Each pixel's ratio by its halves' estimate, where its samples moved.
  std::vector<uint8_t, UnwrittenAllocator<uint8_t>> moved(size);
  forEachRow(0, height, [&](int y) {
    for (size_t p = size_t(y) * size_t(width), last = p + size_t(width); p < last; ++p) {
      moved[p] = pixels[p].samples() != kept.samples[p];
      if (!moved[p]) continue;
      kept.samples[p] = pixels[p].samples();
      kept.ratio[p] = target.ratio(pixels[p], spread);
      double value[4];
      pixels[p].mean(value);
      std::copy(value, value + 3, &kept.means[3 * p]);
    }
  });
  // Its ratio by the edge floor its 4-neighbours' means set (PixelError::edgeFloor), where it
  // or one of them moved.
  forEachRow(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * size_t(width) + size_t(x);
      const bool left = x > 0, right = x + 1 < width, up = y > 0, down = y + 1 < height;
      if (!moved[p] && !(left && moved[p - 1]) && !(right && moved[p + 1]) &&
          !(up && moved[p - size_t(width)]) && !(down && moved[p + size_t(width)]))
        continue;
      double contrast[3] = {0, 0, 0};
      const auto against = [&](bool inside, size_t q) {
        if (!inside) return;
        for (int c = 0; c < 3; ++c)
          contrast[c] =
              std::max(contrast[c], std::abs(kept.means[3 * p + c] - kept.means[3 * q + c]));
      };
      against(left, p - 1);
      against(right, p + 1);
      against(up, p - size_t(width));
      against(down, p + size_t(width));
      kept.edgeRatio[p] = target.ratio(PixelError::edgeFloor(pixels[p], contrast),
                                       pixels[p].samples(), pixels[p].raysPerSample(), spread);
    }
  });
}

FrameSummary summariseFrame(std::span<const PixelEstimate> pixels, SamplerKind sampler) {
  struct Sums {
    double squared = 0, relative = 0;
    bool complete = true;  // every pixel so far has an estimate
    int64_t fewest = std::numeric_limits<int64_t>::max(), most = 0, total = 0;
  };
  const bool estimated = sampler != SamplerKind::Regular;
  // Deterministic: the range is cut into the same blocks, summed in the same order, for any
  // thread count, so the figures' bits do not depend on it. One read of the pixels for all
  // the figures: the loop is bound by memory, and runs after every pass.
  constexpr size_t kBlock = 4096;
  const Sums sums = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<size_t>(0, pixels.size(), kBlock), Sums{},
      [&](const tbb::blocked_range<size_t>& r, Sums s) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const int64_t n = pixels[i].samples();
          s.fewest = std::min(s.fewest, n), s.most = std::max(s.most, n), s.total += n;
          if (!estimated || !s.complete) continue;
          PixelError pixel;
          if (!PixelError::of(pixels[i], pixel)) {
            s.complete = false;
            continue;
          }
          s.squared += pixel.mse;
          s.relative += pixel.relmse;
        }
        return s;
      },
      [](Sums a, const Sums& b) {
        return Sums{a.squared + b.squared,    a.relative + b.relative,
                    a.complete && b.complete, std::min(a.fewest, b.fewest),
                    std::max(a.most, b.most), a.total + b.total};
      });
  FrameSummary out;
  out.fewestSamples = pixels.empty() ? 0 : sums.fewest;
  out.mostSamples = sums.most;
  out.samples = sums.total;
  if (!estimated || pixels.empty() || !sums.complete) return out;
  const double n = static_cast<double>(pixels.size());
  out.error.rmse = std::sqrt(sums.squared / n);
  out.error.relmse = sums.relative / n;
  return out;
}

FrameError estimateFrameError(std::span<const PixelEstimate> pixels, SamplerKind sampler) {
  return summariseFrame(pixels, sampler).error;
}

ProbeLattice ProbeLattice::of(int width, int height) {
  const double cells = double(width) * double(height) / kProbesWanted;
  ProbeLattice lattice;
  lattice.stride = std::clamp(static_cast<int>(std::sqrt(cells)), 1, kMaxStride);
  lattice.offset = lattice.stride / 2;
  lattice.columns = width > lattice.offset ? (width - lattice.offset - 1) / lattice.stride + 1 : 0;
  lattice.rows = height > lattice.offset ? (height - lattice.offset - 1) / lattice.stride + 1 : 0;
  return lattice;
}

}  // namespace glint
