#include "render/render_job.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_reduce.h>

#include "camera/camera.h"
#include "core/check.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/memory.h"
#include "core/sampler.h"
#include "core/uninitialized_array.h"
#include "integrator/batched_kernel.h"
#include "integrator/reference.h"
#include "render/aov_accumulator.h"
#include "render/progress.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {

constexpr int kMaxLoggedNonfinite = 5;

// The record of a sample when only the beauty's variance is asked for.
const AovSample kNoRecord{};

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
  std::vector<PixelEstimate>& estimates;
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

// Shades a chunk of camera samples with the production kernel: their rays traced as one
// coherent stream (Embree traces it as packets), their hits shaded together (traceCameraHits),
// so that one sample's memory misses and dependent chains overlap another's.
struct ProductionShading {
  const BatchedKernel& kernel;
  const Accelerator& accel;
  BatchedKernel::Scratch& scratch;
  Hit hits[kCameraChunk];

  void operator()(const Ray* rays, const SampleKey* keys, int count, Radiance* out,
                  AovSample* const* records, RayCounters& counters) {
    accel.intersectCoherent(rays, hits, static_cast<size_t>(count));
    kernel.traceCameraHits(rays, hits, keys, count, out, records, counters, scratch);
  }
};

// The same with the reference integrator, depth first, one sample at a time.
struct ReferenceShading {
  const ReferenceIntegrator& integrator;

  void operator()(const Ray* rays, const SampleKey* keys, int count, Radiance* out,
                  AovSample* const*, RayCounters& counters) const {
    for (int i = 0; i < count; ++i) out[i] = integrator.radiance(rays[i], keys[i], counters);
  }
};

// Whether a cancel was asked for, or the time limit has passed; polled between chunks, so a
// render stops within one chunk of samples per thread at any spp, not at the end of a tile.
bool stopped(const RenderOptions& opt, const PassContext& pass) {
  if (opt.cancel && opt.cancel->load(std::memory_order_relaxed)) return true;
  if (!pass.deadline) return false;
  if (pass.deadlinePassed.load(std::memory_order_relaxed)) return true;
  if (std::chrono::steady_clock::now() < *pass.deadline) return false;
  pass.deadlinePassed = true;
  return true;
}

// One pass over one tile: each pixel that takes part gets its samples from where it stands up
// to the pass's end, half 0's then half 1's, made and shaded in chunks by `shade`
// (ProductionShading or ReferenceShading). A chunk holds several pixels' samples at low spp and
// a run of one pixel's at high spp; a pixel's new state is kept only once all its samples of
// the pass are in, so a stop leaves every pixel at the end of a pass. AOV records are made only
// when AOVs are asked for. Returns false when a stop cut the tile short.
template <class Shading>
bool renderTilePass(const FrameContext& f, const PassContext& pass, Shading& shade,
                    const PixelWindow& tile, RayCounters& counters) {
  const bool aovs = f.opt.aovs.any();
  const bool transparent = f.scene.render.transparentBackground;
  const bool aovSamples = f.opt.aovs.needsSamples();
  const Vec3f viewAxis = -f.camera.w();
  PixelAovs pixelAovs(f.aovLayout);
  // The arrays live per tile: declared per pixel, their initialisation cost 13 % of a 1-spp
  // render.
  Ray rays[kCameraChunk];
  SampleKey keys[kCameraChunk];
  Radiance radiance[kCameraChunk];
  bool firstOfPixel[kCameraChunk], lastOfPixel[kCameraChunk];
  // Written only when AOVs are asked for (cleared per sample, they cost 264 bytes of stores
  // each).
  UninitializedArray<AovSample, kCameraChunk> records;
  AovSample* recordOf[kCameraChunk];
  CameraSampling::Points cameraPoints;
  PixelEstimate pixel;  // the state of the pixel being sampled, kept when its last sample is in
  int count = 0;        // samples in the chunk
  const auto flush = [&]() {
    if (count == 0) return true;
    if (stopped(f.opt, pass)) return false;
    if (aovSamples)
      for (int i = 0; i < count; ++i) {
        records[i] = AovSample{};
        records[i].viewAxis = viewAxis;
        recordOf[i] = &records[i];
      }
    shade(rays, keys, count, radiance, aovSamples ? recordOf : nullptr, counters);
    for (int i = 0; i < count; ++i) {
      const SampleKey& key = keys[i];
      if (firstOfPixel[i]) {
        pixel = f.estimate(key.px, key.py);
        if (aovs) pixelAovs.begin();
      }
      Radiance& r = radiance[i];
      if (f.opt.sampleHook) f.opt.sampleHook(key.px, key.py, r);
      if (!r.L.isFinite()) r.L = {}, r.valid = false;
      // The beauty is premultiplied: the background is opaque, or, on a transparent film, a
      // miss adds neither colour nor coverage (docs/output.md, Alpha).
      if (!transparent)
        r.alpha = 1;
      else if (r.alpha == 0)
        r.L = {};
      if (aovs) pixelAovs.add(r, aovSamples ? records[i] : kNoRecord);
      if (!r.valid) {
        // A non-finite sample never reaches the film: it counts as black.
        ++counters.nonfiniteSamples;
        if (f.loggedNonfinite.fetch_add(1) < kMaxLoggedNonfinite)
          log::warning("non-finite sample at pixel (" + std::to_string(key.px) + ", " +
                       std::to_string(key.py) + ") sample " + std::to_string(key.index) +
                       " of half " + std::to_string(key.half));
      }
      pixel.half[key.half].add(r.L, r.alpha, r.rays);
      if (lastOfPixel[i]) {
        f.estimate(key.px, key.py) = pixel;
        if (aovs) pixelAovs.commit(f.aovSums, f.aovTables, key.px, key.py);
      }
    }
    count = 0;
    return true;
  };
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      if (!f.slots.holds(x, y) || !pass.sampled[f.slots.slot(x, y)]) continue;
      const int64_t taken = f.estimate(x, y).samples();
      const uint64_t pixelKey = f.sampler.pixelKey(x, y);
      bool first = true;
      for (int half = 0; half < 2; ++half)
        for (int j = halfSampleCount(taken, half), end = halfSampleCount(pass.end, half);
             j < end;) {
          if (count == kCameraChunk && !flush()) return false;
          const int run = std::min(end - j, kCameraChunk - count);
          for (int i = 0; i < run; ++i) {
            keys[count + i] = SampleKey(&f.sampler, x, y, j + i, pixelKey, half);
            firstOfPixel[count + i] = first && i == 0;
            lastOfPixel[count + i] = false;
          }
          first = false;
          f.cameraSampling.rays(keys + count, run, rays + count, cameraPoints);
          count += run;
          j += run;
        }
      if (!first) lastOfPixel[count - 1] = true;
    }
  return flush();
}

// The tiles of one render, and what their loop shares besides the frame.
struct TileWork {
  const std::vector<PixelWindow>& tiles;
  std::vector<RayCounters>& counters;  // per tile, over all passes
  Progress& progress;
  std::atomic<bool>& stopped;  // set when a cancel or the time limit cut the pass short
  int threads;
};

// Runs tile(i, counters) for every tile on the scheduler, until a stop.
template <class RenderOneTile>
void forEachTile(const FrameContext& f, const PassContext& pass, TileWork& work,
                 RenderOneTile&& tile) {
  runTiles(work.tiles, work.threads, [&](size_t i) {
    if (stopped(f.opt, pass)) {
      work.stopped = true;
      return;
    }
    // Counted on this thread's stack: neighbouring tiles' counters share cache lines, which
    // two threads would otherwise write in their inner loops.
    RayCounters counters;
    const bool complete = tile(i, counters);
    work.counters[i] += counters;
    if (!complete) {
      work.stopped = true;
      return;
    }
    work.progress.advance(static_cast<int64_t>(counters.camera), counters.total());
  });
}

// Every tile with the production kernel. A thread keeps one scratch for all the tiles it
// renders: made per tile, its allocation, clearing and page faults cost 5 % of a render's time
// at 32-pixel tiles and 18 % at 8 (default scene, one thread).
class ProductionTiles {
 public:
  ProductionTiles(const Scene& scene, const Accelerator& accel, int footprintSpp)
      : kernel_(scene, accel, kDefaultMinThroughput, footprintSpp) {}
  void render(const FrameContext& f, const PassContext& pass, TileWork& work) {
    forEachTile(f, pass, work, [&](size_t i, RayCounters& counters) {
      std::unique_ptr<Scratch>& scratch = scratches_.local();
      if (!scratch) scratch = std::make_unique<Scratch>();
      ProductionShading shade{kernel_, f.accel, *scratch, {}};
      return renderTilePass(f, pass, shade, work.tiles[i], counters);
    });
  }

 private:
  using Scratch = BatchedKernel::Scratch;
  const BatchedKernel kernel_;  // const: shared by the threads
  tbb::enumerable_thread_specific<std::unique_ptr<Scratch>> scratches_;
};

// Every tile with the reference integrator (beauty only, no AOVs).
class ReferenceTiles {
 public:
  ReferenceTiles(const Scene& scene, const Accelerator& accel, int footprintSpp)
      : integrator_(scene, accel, kDefaultMinThroughput, footprintSpp) {}
  void render(const FrameContext& f, const PassContext& pass, TileWork& work) {
    forEachTile(f, pass, work, [&](size_t i, RayCounters& counters) {
      ReferenceShading shade{integrator_};
      return renderTilePass(f, pass, shade, work.tiles[i], counters);
    });
  }

 private:
  const ReferenceIntegrator integrator_;
};

// The pixels' states inside `window` (of the sampled window), row-major.
std::vector<PixelEstimate> estimatesIn(const FrameContext& f, const PixelWindow& window) {
  std::vector<PixelEstimate> out;
  out.reserve(static_cast<size_t>(window.area()));
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x) out.push_back(f.estimate(x, y));
  return out;
}

// The part of a per-pixel mask over `from` that lies in `window` (inside it), row-major.
std::vector<uint8_t> windowPart(const std::vector<uint8_t>& mask, const PixelWindow& from,
                                const PixelWindow& window) {
  std::vector<uint8_t> out;
  out.reserve(static_cast<size_t>(window.area()));
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x)
      out.push_back(mask[size_t(y - from.y0) * size_t(from.width()) + size_t(x - from.x0)]);
  return out;
}

// An adaptive frame continues as a straight render only if its passes are where this plan's
// are: the last it finished is one of the plan's ends, and the one it cut short the next. Their
// ends double from the first pass up to --max-spp: a frame finished at --max-spp 20 (8, 16, 20)
// has taken a pass that a render to 32 (8, 16, 32) never takes. Any position suits the other
// renders, whose passes choose every pixel below their end.
void checkResumablePosition(const PassPlan& plan, const PassPosition& at) {
  if (!plan.adaptive()) return;
  const auto next = std::upper_bound(plan.ends.begin(), plan.ends.end(), at.finishedEnd);
  const bool finishedOnPlan = at.finishedEnd == 0 || std::find(plan.ends.begin(), plan.ends.end(),
                                                               at.finishedEnd) != plan.ends.end();
  if (finishedOnPlan && (at.cutEnd == 0 || (next != plan.ends.end() && *next == at.cutEnd))) return;
  std::string ends;
  for (const int end : plan.ends) ends += (ends.empty() ? "" : ", ") + std::to_string(end);
  throw UsageError("--resume: the frame's adaptive passes stopped at " +
                   std::to_string(at.cutEnd > 0 ? at.cutEnd : at.finishedEnd) +
                   " spp, which this render's passes (" + ends +
                   ") do not reach on their way: a continued frame takes the choices a "
                   "straight render takes only where their passes end alike; give a --max-spp "
                   "whose passes, doubling from --min-spp, include it");
}

// The frame as it stands in `window`: each pixel's mean and the AOVs' finished values.
Film resolveFrame(const FrameContext& f, const PixelWindow& window) {
  const Film& sums = f.aovSums;
  Film out(sums.fullWidth(), sums.fullHeight(), window);
  for (const FilmPlane& plane : sums.planes())
    out.addPlane(plane.name, plane.channels, plane.isUint);
  for (const auto& [key, value] : sums.stringAttributes()) out.addAttribute(key, value);
  for (const auto& [key, value] : sums.intAttributes()) out.addAttribute(key, value);
  // On the render's threads: each pixel is written from its own state alone.
  forEachRow(window.y0, window.y1, [&](int y) {
    for (int x = window.x0; x < window.x1; ++x) {
      const PixelEstimate& pixel = f.estimate(x, y);
      double rgba[4];
      pixel.mean(rgba);
      out.setPixel(x, y, rgba[0], rgba[1], rgba[2], rgba[3]);
      if (f.opt.aovs.any()) resolveAovs(f.aovLayout, sums, f.aovTables, pixel, out, x, y);
    }
  });
  return out;
}

// The statistics of the frame as it stands, besides the rays and time; returns the samples its
// pixels hold.
int64_t describeSamples(const std::vector<PixelEstimate>& estimates, SamplerKind sampler,
                        RenderStats& stats) {
  stats.sampler = sampler;
  stats.estimated = estimateFrameError(estimates, sampler);
  struct Counts {
    int64_t fewest = std::numeric_limits<int64_t>::max(), most = 0, total = 0;
  };
  const Counts counts = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, estimates.size()), Counts{},
      [&](const tbb::blocked_range<size_t>& r, Counts c) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const int64_t n = estimates[i].samples();
          c = {std::min(c.fewest, n), std::max(c.most, n), c.total + n};
        }
        return c;
      },
      [](const Counts& a, const Counts& b) {
        return Counts{std::min(a.fewest, b.fewest), std::max(a.most, b.most), a.total + b.total};
      });
  stats.minPixelSpp = estimates.empty() ? 0 : static_cast<int>(counts.fewest);
  stats.maxPixelSpp = static_cast<int>(counts.most);
  return counts.total;
}

}  // namespace

bool parseIntegratorKind(const std::string& name, IntegratorKind& out) {
  if (name == "production")
    out = IntegratorKind::Production;
  else if (name == "reference")
    out = IntegratorKind::Reference;
  else
    return false;
  return true;
}

void checkSampleSets(const Scene& scene, int64_t spp) {
  const std::string limit = "the sampler's limit of " + std::to_string(kMaxSampleSet);
  if (spp > kMaxSampleSet)
    throw UsageError("spp " + std::to_string(spp) + " is more than " + limit);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const int64_t samples = lightSampleCount(scene.lights[i]);
    if (spp * samples <= kMaxSampleSet) continue;
    throw UsageError(
        "spp " + std::to_string(spp) + " × the " + std::to_string(samples) + " samples of lights[" +
        std::to_string(i) + "] = " + std::to_string(spp * samples) +
        " light samples per pixel, more than " + limit + ": lower spp or the light's \"samples\"");
  }
}

void checkFrameFits(int64_t pixels, size_t channels, uint64_t availableBytes) {
  const double needed = double(pixels) * (12.0 * double(channels) + 16.0);
  if (availableBytes == 0 || needed <= double(availableBytes)) return;
  throw UsageError("a frame of " + std::to_string(pixels) + " pixels with " +
                   std::to_string(channels) + " channels needs about " + gigabytes(needed) +
                   " of memory (film in double, float copies to write it); " +
                   gigabytes(double(availableBytes)) +
                   " is available: render it in pieces with --crop, or on a farm");
}

RenderResult renderScene(const Scene& scene, const Accelerator& accel, const RenderOptions& opt,
                         const PassCallback& onPass) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto secondsSince = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  const RenderSettings& rs = scene.render;
  // A stop asked for by a signal must be seen in bounded time, whatever the threads wait on.
  const interrupt::Sampling boundedStop;
  const PassPlan plan = PassPlan::make(rs.spp, rs.sampler, opt.sampling);
  checkSampleSets(scene, plan.maxSpp);
  const PixelWindow window = opt.crop.value_or(PixelWindow{0, rs.width, 0, rs.height});
  // Adaptive sampling decides from each pixel's neighbours: a crop samples an apron around it
  // too, so that its pixels are sampled as in the full frame (PassPlan::apron).
  const int apron = plan.apron();
  const PixelWindow sampledWindow{
      std::max(0, window.x0 - apron), std::min(rs.width, window.x1 + apron),
      std::max(0, window.y0 - apron), std::min(rs.height, window.y1 + apron)};
  {
    // The AOV planes' channels, from the layout itself on a one-pixel film; and the state a
    // pixel keeps between passes, in doubles.
    Film probe(1, 1, PixelWindow{0, 1, 0, 1});
    AovLayout::create(opt.aovs, scene, probe);
    size_t channels = 4 + sizeof(PixelEstimate) / 12;
    for (const FilmPlane& plane : probe.planes()) channels += 2 * plane.channels.size();
    checkFrameFits(sampledWindow.area(), channels, availableMemoryBytes());
  }
  Film aovSums(rs.width, rs.height, sampledWindow);
  const Camera camera(scene.cameraDesc, rs.width, rs.height);
  const Sampler sampler(plan.sampler, plan.maxSpp, rs.seed);
  // AOV work happens only when AOVs are asked for (leave out what is not needed).
  const AovLayout aovLayout = AovLayout::create(opt.aovs, scene, aovSums);
  if (opt.integrator == IntegratorKind::Reference && opt.aovs.any())
    throw UsageError("the reference integrator renders the beauty only: drop --aov");
  AovTables aovTables(aovLayout, sampledWindow);
  std::vector<PixelEstimate> estimates(static_cast<size_t>(sampledWindow.area()));
  if (opt.resumeFrom) {
    if (sampledWindow.area() != window.area())
      throw UsageError(
          "--resume continues an adaptive render of the full frame only: a crop's "
          "adaptive sampling depends on pixels around it, whose state is not kept");
    GLINT_CHECK(opt.resumeFrom->estimates.size() == estimates.size());
    if (opt.aovs.needsSamples())
      throw UsageError(
          "--resume continues the beauty and its variance only: the other AOVs' "
          "sums are not kept with the frame");
    checkResumablePosition(plan, opt.resumeFrom->position);
    estimates = opt.resumeFrom->estimates;
  }

  const int threads = threadCount(opt.threads);
  const int tileSize = effectiveTileSize(sampledWindow, opt.tileSize, threads);
  const std::vector<PixelWindow> tiles = makeTiles(sampledWindow, tileSize, opt.tileOrder);
  std::vector<RayCounters> tileCounters(tiles.size());
  ProgressPlan progressPlan;
  progressPlan.totalWork = sampledWindow.area() * plan.maxSpp;
  progressPlan.workIsBound = plan.adaptive();
  if (plan.timeLimitSeconds > 0) progressPlan.timeLimitSeconds = plan.timeLimitSeconds;
  // A continued frame's first pass is behind it: the limit holds from its first pass taken.
  if (!opt.resumeFrom) progressPlan.firstPassWork = sampledWindow.area() * plan.ends.front();
  Progress progress(progressPlan, opt.progress, start);
  std::atomic<int> loggedNonfinite{0};
  const CameraSampling cameraSampling(scene, camera);
  const FrameContext frame{scene,          accel,   opt,       camera,
                           cameraSampling, sampler, aovLayout, loggedNonfinite,
                           estimates,      aovSums, aovTables, PixelSlots::all(sampledWindow)};
  std::optional<ProductionTiles> production;
  std::optional<ReferenceTiles> reference;
  if (opt.integrator == IntegratorKind::Reference)
    reference.emplace(scene, accel, plan.footprintSpp());
  else
    production.emplace(scene, accel, plan.footprintSpp());
  const auto renderPass = [&](const FrameContext& f, const PassContext& pass, TileWork& work) {
    if (reference)
      reference->render(f, pass, work);
    else
      production->render(f, pass, work);
  };
  // The probes' first pass, rendered on their own (beauty only) so that a crop or a resumed
  // render measures the frame's spread as the full frame does. Absent when a cancel cut it
  // short.
  const RenderOptions probeOptions = [&] {
    RenderOptions o = opt;
    o.aovs = {};
    return o;
  }();
  std::vector<RayCounters> probeCounters(tiles.size());
  const auto measureSpread = [&]() -> std::optional<FrameSpread> {
    const ProbeLattice lattice = ProbeLattice::of(rs.width, rs.height);
    std::vector<PixelEstimate> probes(size_t(lattice.columns) * size_t(lattice.rows));
    const FrameContext probeFrame{
        scene,          accel,   probeOptions, camera,
        cameraSampling, sampler, aovLayout,    loggedNonfinite,
        probes,         aovSums, aovTables,    PixelSlots::probes(lattice, rs.width, rs.height)};
    const std::vector<uint8_t> all(probes.size(), 1);
    std::atomic<bool> never{false}, stopped{false};
    const PassContext pass{plan.minSpp, all, std::nullopt, never};
    Progress silent({}, false);
    const std::vector<PixelWindow> frameTiles =
        makeTiles(PixelWindow{0, rs.width, 0, rs.height}, tileSize, opt.tileOrder);
    probeCounters.assign(frameTiles.size(), {});
    TileWork work{frameTiles, probeCounters, silent, stopped, threads};
    renderPass(probeFrame, pass, work);
    if (stopped) return std::nullopt;
    return FrameSpread::of(probes);
  };
  std::optional<FrameSpread> spread;

  RenderResult result{Film(rs.width, rs.height, window), {}, false, tileSize, {}, {}};
  // The pixels' states in the window: the frame's own where it samples no apron (copied at
  // every pass, they cost a fast render 1-2 ms a pass at 240 x 150), else a copy.
  std::vector<PixelEstimate> cropEstimates;
  const auto windowEstimates = [&]() -> const std::vector<PixelEstimate>& {
    if (sampledWindow.area() == window.area()) return estimates;
    cropEstimates = estimatesIn(frame, window);
    return cropEstimates;
  };
  // Returns the samples the window's pixels hold.
  const auto statsSoFar = [&] {
    result.stats.rays = {};
    for (const RayCounters& c : tileCounters) result.stats.rays += c;
    for (const RayCounters& c : probeCounters) result.stats.rays += c;
    result.stats.integrator = opt.integrator;
    result.stats.seconds = secondsSince(start);
    return describeSamples(windowEstimates(), plan.sampler, result.stats);
  };
  std::vector<uint8_t> sampled(estimates.size(), 1);
  ChoiceCache choiceCache;
  const PassPosition* resumed = opt.resumeFrom ? &opt.resumeFrom->position : nullptr;
  // Where the passes stand, from where the continued frame's stood: its pixels may hold more
  // than the ends this plan skips (--spp 24, continued to 64: 24 against 16), and a stop
  // before its cut pass is taken again must keep that pass's choice.
  PassPosition& position = result.position;
  if (resumed) position = *resumed;
  const auto finished = [&](int end) {
    position.finishedEnd = end;
    if (position.cutEnd <= end) position.cutEnd = 0, position.cutChosen.clear();
  };
  std::atomic<bool> deadlinePassed{false};
  // From here on, on the render's threads: the tiles, and the per-pixel work between passes
  // (choosing pixels, the statistics, the resolved frame), which other threads would wait for.
  withThreads(threads, [&] {
    for (size_t k = 0; k < plan.ends.size(); ++k) {
      const int end = plan.ends[k];
      // A continued frame's finished passes are not taken again: their choices would read a
      // state later passes have moved on (a straight render takes each from the one before).
      if (resumed && end <= resumed->finishedEnd) continue;
      if (plan.adaptive() && k > 0 && !spread) {
        spread = measureSpread();
        if (!spread) {
          result.partial = true;
          break;
        }
      }
      // The pass a stop cut short goes on with the pixels it had chosen.
      int64_t pixels = 0;
      if (resumed && end == resumed->cutEnd) {
        sampled = resumed->cutChosen;
        pixels = std::count(sampled.begin(), sampled.end(), uint8_t{1});
      } else {
        pixels = plan.choosePixels(estimates, sampledWindow.width(), end,
                                   spread.value_or(FrameSpread{}), choiceCache, sampled);
      }
      if (pixels == 0) {  // every pixel is past this pass (resumed), or met its target
        finished(end);
        continue;
      }
      if (plan.adaptive()) progress.replan(pixels * (plan.maxSpp - (k > 0 ? plan.ends[k - 1] : 0)));
      // The time limit applies from the second pass on: the first is what makes a frame.
      std::optional<Clock::time_point> deadline;
      if (plan.timeLimitSeconds > 0 && k > 0)  // a limit past 30 years is none (no overflow)
        deadline = start + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(std::min(plan.timeLimitSeconds, 1e9)));
      const PassContext pass{end, sampled, deadline, deadlinePassed};
      std::atomic<bool> stopped{false};
      TileWork work{tiles, tileCounters, progress, stopped, threads};
      renderPass(frame, pass, work);
      if (stopped) {
        result.stats.timeLimitReached = deadlinePassed.load();
        result.partial = !result.stats.timeLimitReached;
        position.cutEnd = end;
        position.cutChosen = windowPart(sampled, sampledWindow, window);
        break;
      }
      finished(end);
      const int64_t samples = statsSoFar();
      result.stats.passes.push_back({end, double(samples) / double(window.area()),
                                     result.stats.seconds, result.stats.estimated, pixels});
      if (onPass && k + 1 < plan.ends.size()) {
        result.film = resolveFrame(frame, window);
        result.estimates = windowEstimates();
        onPass(result);
      }
    }
    progress.finish(result.stats.timeLimitReached ? "the time limit"
                    : result.partial              ? "an interrupt"
                                                  : "");
    result.film = resolveFrame(frame, window);
    statsSoFar();
  });
  // Moved, not copied (a copy cost 11 ms of a default-scene render): the frame's states, or
  // the window's that the last statsSoFar() took from them.
  result.estimates =
      sampledWindow.area() == window.area() ? std::move(estimates) : std::move(cropEstimates);
  return result;
}

}  // namespace glint
