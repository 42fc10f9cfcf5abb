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

#include <tbb/enumerable_thread_specific.h>

#include "camera/camera.h"
#include "core/error.h"
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

// What every tile of one render shares.
struct FrameContext {
  const Scene& scene;
  const Accelerator& accel;
  const RenderOptions& opt;
  Film& film;
  const Camera& camera;
  const CameraSampling& cameraSampling;
  const Sampler& sampler;
  const AovLayout& aovLayout;
  std::atomic<int>& loggedNonfinite;
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

// Whether a cancel was asked for; polled between chunks, so a render stops within one chunk of
// samples per thread at any spp, not at the end of a tile.
bool cancelled(const RenderOptions& opt) {
  return opt.cancel && opt.cancel->load(std::memory_order_relaxed);
}

// One tile, its camera samples shaded in chunks by `shade` (ProductionShading or
// ReferenceShading). AOV records are made only when AOVs are asked for. Returns false when a
// cancel stopped it: the pixel being summed then, and those after it, stay unrendered.
template <class Shading>
bool renderTile(const FrameContext& f, Shading& shade, const PixelWindow& tile,
                RayCounters& counters) {
  const RenderSettings& rs = f.scene.render;
  const bool aovs = f.opt.aovs.any();
  const bool transparent = rs.transparentBackground;
  const bool aovSamples = f.opt.aovs.needsSamples();
  const Vec3f viewAxis = -f.camera.w();
  PixelAovs pixelAovs(f.aovLayout);
  // Camera samples are made and shaded in chunks. Below kCameraChunk spp a chunk holds several
  // whole pixels along the row; from it on, a run of one pixel's samples. Samples are still
  // summed per pixel in index order. The arrays live per tile: declared per pixel, their
  // initialisation cost 13 % of a 1-spp render.
  Ray rays[kCameraChunk];
  SampleKey keys[kCameraChunk];
  Radiance radiance[kCameraChunk];
  // Written only when AOVs are asked for (cleared per sample, they cost 264 bytes of stores
  // each).
  UninitializedArray<AovSample, kCameraChunk> records;
  AovSample* recordOf[kCameraChunk];
  CameraSampling::Points cameraPoints;
  const int pixelsPerChunk = std::max(1, kCameraChunk / rs.spp);
  const int samplesPerChunk = std::min(kCameraChunk, rs.spp);
  const double inv = 1.0 / rs.spp;
  double sum[4] = {0, 0, 0, 0};  // the pixel being summed
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x0 = tile.x0; x0 < tile.x1; x0 += pixelsPerChunk) {
      const int pixels = std::min(pixelsPerChunk, tile.x1 - x0);
      // Samples [first, first + runLength) of each of the pixels; several pixels only when
      // their samples all fit (runLength = spp).
      for (int first = 0; first < rs.spp; first += samplesPerChunk) {
        if (cancelled(f.opt)) return false;
        const int runLength = std::min(samplesPerChunk, rs.spp - first);
        const int count = pixels * runLength;
        for (int p = 0; p < pixels; ++p)
          f.cameraSampling.pixelRays(f.sampler, x0 + p, y, first, runLength, keys + p * runLength,
                                     rays + p * runLength, cameraPoints);
        if (aovSamples)
          for (int i = 0; i < count; ++i) {
            records[i] = AovSample{};
            records[i].viewAxis = viewAxis;
            recordOf[i] = &records[i];
          }
        shade(rays, keys, count, radiance, aovSamples ? recordOf : nullptr, counters);
        for (int p = 0; p < pixels; ++p) {
          const int x = x0 + p;
          if (first == 0) {
            sum[0] = sum[1] = sum[2] = sum[3] = 0;
            if (aovs) pixelAovs.begin();
          }
          for (int i = p * runLength; i < (p + 1) * runLength; ++i) {
            Radiance& r = radiance[i];
            if (f.opt.sampleHook) f.opt.sampleHook(x, y, r);
            if (!r.L.isFinite()) r.L = {}, r.valid = false;
            // The beauty is premultiplied: the background is opaque, or, on a transparent
            // film, a miss adds neither colour nor coverage (docs/output.md, Alpha).
            if (!transparent)
              r.alpha = 1;
            else if (r.alpha == 0)
              r.L = {};
            if (aovs) pixelAovs.add(r, aovSamples ? records[i] : kNoRecord);
            sum[3] += r.alpha;
            if (!r.valid) {
              // A non-finite sample never reaches the film: it counts as black.
              ++counters.nonfiniteSamples;
              if (f.loggedNonfinite.fetch_add(1) < kMaxLoggedNonfinite)
                log::warning("non-finite sample at pixel (" + std::to_string(x) + ", " +
                             std::to_string(y) + ") sample " + std::to_string(keys[i].index));
              continue;
            }
            sum[0] += r.L.r;
            sum[1] += r.L.g;
            sum[2] += r.L.b;
          }
          if (first + runLength < rs.spp) continue;  // the pixel goes on in the next chunk
          f.film.setPixel(x, y, sum[0] * inv, sum[1] * inv, sum[2] * inv, sum[3] * inv);
          if (aovs) pixelAovs.end(f.film, x, y);
        }
      }
    }
  return true;
}

// The tiles of one render, and what their loop shares besides the frame.
struct TileWork {
  const std::vector<PixelWindow>& tiles;
  std::vector<RayCounters>& counters;  // per tile
  Progress& progress;
  std::atomic<bool>& skipped;  // set when a cancel left tiles out
  int threads;
};

// Runs tile(i, counters) for every tile on the scheduler, until a cancel stops them.
template <class RenderOneTile>
void forEachTile(const FrameContext& f, TileWork& work, RenderOneTile&& tile) {
  runTiles(work.tiles, work.threads, [&](size_t i) {
    if (cancelled(f.opt)) {
      work.skipped = true;
      return;
    }
    // Counted on this thread's stack: neighbouring tiles' counters share cache lines, which
    // two threads would otherwise write in their inner loops.
    RayCounters counters;
    const bool complete = tile(i, counters);
    work.counters[i] = counters;
    if (!complete) {
      work.skipped = true;
      return;
    }
    work.progress.advance(work.tiles[i].area(), counters.total());
  });
}

// Every tile with the production kernel. A thread keeps one scratch for all the tiles it
// renders: made per tile, its allocation, clearing and page faults cost 5 % of a render's time
// at 32-pixel tiles and 18 % at 8 (default scene, one thread).
void renderTilesProduction(const FrameContext& f, TileWork& work) {
  using Scratch = BatchedKernel::Scratch;
  const BatchedKernel kernel(f.scene, f.accel);  // const: shared by the threads
  tbb::enumerable_thread_specific<std::unique_ptr<Scratch>> scratches;
  forEachTile(f, work, [&](size_t i, RayCounters& counters) {
    std::unique_ptr<Scratch>& scratch = scratches.local();
    if (!scratch) scratch = std::make_unique<Scratch>();
    ProductionShading shade{kernel, f.accel, *scratch, {}};
    return renderTile(f, shade, work.tiles[i], counters);
  });
}

// Every tile with the reference integrator (beauty only, no AOVs).
void renderTilesReference(const FrameContext& f, TileWork& work) {
  const ReferenceIntegrator integrator(f.scene, f.accel);
  forEachTile(f, work, [&](size_t i, RayCounters& counters) {
    ReferenceShading shade{integrator};
    return renderTile(f, shade, work.tiles[i], counters);
  });
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

void checkSampleSets(const Scene& scene) {
  const int64_t spp = scene.render.spp;
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

RenderResult renderScene(const Scene& scene, const Accelerator& accel, const RenderOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const RenderSettings& rs = scene.render;
  checkSampleSets(scene);
  const PixelWindow window = opt.crop.value_or(PixelWindow{0, rs.width, 0, rs.height});
  {
    // The AOV planes' channels, from the layout itself on a one-pixel film.
    Film probe(1, 1, PixelWindow{0, 1, 0, 1});
    AovLayout::create(opt.aovs, scene, probe);
    size_t channels = 4;
    for (const FilmPlane& plane : probe.planes()) channels += plane.channels.size();
    checkFrameFits(window.area(), channels, availableMemoryBytes());
  }
  Film film(rs.width, rs.height, window);
  const Camera camera(scene.cameraDesc, rs.width, rs.height);
  const Sampler sampler(rs.sampler, rs.spp, rs.seed);
  // AOV work happens only when AOVs are asked for (leave out what is not needed).
  const AovLayout aovLayout = AovLayout::create(opt.aovs, scene, film);
  if (opt.integrator == IntegratorKind::Reference && opt.aovs.any())
    throw UsageError("the reference integrator renders the beauty only: drop --aov");

  const int threads = opt.threads > 0 ? opt.threads : defaultThreadCount();
  const int tileSize = effectiveTileSize(window, opt.tileSize, threads);
  const std::vector<PixelWindow> tiles = makeTiles(window, tileSize, opt.tileOrder);
  std::atomic<bool> skipped{false};
  std::vector<RayCounters> tileCounters(tiles.size());
  Progress progress(window.area(), opt.progress);
  std::atomic<int> loggedNonfinite{0};
  const CameraSampling cameraSampling(scene, camera);
  const FrameContext frame{scene,          accel,   opt,       film,           camera,
                           cameraSampling, sampler, aovLayout, loggedNonfinite};

  TileWork work{tiles, tileCounters, progress, skipped, threads};
  if (opt.integrator == IntegratorKind::Reference)
    renderTilesReference(frame, work);
  else
    renderTilesProduction(frame, work);
  progress.finish();

  RenderResult result{std::move(film), {}, skipped.load(), tileSize};
  for (const RayCounters& c : tileCounters) result.stats.rays += c;
  result.stats.integrator = opt.integrator;
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace glint
