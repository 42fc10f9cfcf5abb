#pragma once
// One pass of a render over its tiles: each pixel the pass chose gets its camera samples from
// where it stands up to the pass's end, traced and shaded in chunks by the production kernel or
// the reference integrator, and added to the pixel's estimate (render/pixel_estimate.h) and AOV
// sums. A stop (a cancel, the time limit) is polled between chunks; a pixel's new state is kept
// only once all its samples of the pass are in, so a stop leaves every pixel at the end of a
// pass. The render session (render/render_session.h) decides which passes run and on which
// pixels; this file only runs one.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "accel/accelerator.h"
#include "camera/camera.h"
#include "core/sampler.h"
#include "film/film.h"
#include "integrator/ray_counters.h"
#include "render/aov_accumulator.h"
#include "render/pixel_estimate.h"
#include "render/progress.h"
#include "render/render_job.h"
#include "render/tile_scheduler.h"
#include "scene/scene.h"

namespace glint {

// Which pixels a render samples and where each keeps its state, row-major: every pixel of a
// window, or a lattice of the full frame (the probes of adaptive sampling, ProbeLattice).
struct PixelSlots {
  PixelWindow window;
  int stride = 1, offset = 0, columns = 0;

  static PixelSlots all(const PixelWindow& w) { return {w, 1, 0, w.width()}; }
  static PixelSlots probes(const ProbeLattice& l, int width, int height) {
    return {PixelWindow{0, width, 0, height}, l.stride, l.offset, l.columns};
  }
  bool holds(int x, int y) const {
    if (stride == 1) return true;
    const int dx = x - window.x0 - offset, dy = y - window.y0 - offset;
    return dx >= 0 && dy >= 0 && dx % stride == 0 && dy % stride == 0;
  }
  size_t slot(int x, int y) const {
    return size_t((y - window.y0 - offset) / stride) * size_t(columns) +
           size_t((x - window.x0 - offset) / stride);
  }
};

// What every tile of one render shares.
struct FrameContext {
  const Scene& scene;
  const Accelerator& accel;
  const RenderOptions& opt;
  const Camera& camera;
  const CameraSampling& cameraSampling;
  const Sampler& sampler;
  const AovLayout& aovLayout;
  std::atomic<int>& loggedNonfinite;
  // The state passes leave, one entry per pixel of `slots`, and the AOV sums.
  std::span<PixelEstimate> estimates;
  Film& aovSums;
  AovTables& aovTables;
  PixelSlots slots;

  PixelEstimate& estimate(int x, int y) const { return estimates[slots.slot(x, y)]; }
};

// The pass being rendered: the samples per pixel it brings pixels up to, which pixels take
// part, and when a time limit stops it.
struct PassContext {
  int end = 0;
  const std::vector<uint8_t>& sampled;  // per slot, as FrameContext::estimates
  std::optional<std::chrono::steady_clock::time_point> deadline;
  std::atomic<bool>& deadlinePassed;
};

// The tiles of one pass, and what their loop shares besides the frame.
struct TileWork {
  const std::vector<PixelWindow>& tiles;
  std::vector<RayCounters>& counters;  // per tile, summed over the passes
  Progress& progress;
  std::atomic<bool>& stopped;  // set when a cancel or the time limit cut the pass short
  int threads;
  TileSchedule schedule = {};  // the order tiles are taken in, and where their times go
};

// Renders passes with one integrator: the production kernel, or its oracle.
class TilePasses {
 public:
  virtual ~TilePasses() = default;
  // Runs the pass on every tile of `work` on the scheduler, until a stop.
  virtual void render(const FrameContext& f, const PassContext& pass, TileWork& work) = 0;
};

// The production kernel's (integrator/batched_kernel.h) or the reference integrator's
// (beauty only), their texture footprints shared among `footprintSpp` samples.
std::unique_ptr<TilePasses> makeTilePasses(IntegratorKind kind, const Scene& scene,
                                           const Accelerator& accel, int footprintSpp);

}  // namespace glint
