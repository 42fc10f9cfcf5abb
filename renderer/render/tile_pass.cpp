#include "render/tile_pass.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <string>

#include <tbb/enumerable_thread_specific.h>

#include "core/log.h"
#include "core/uninitialized_array.h"
#include "integrator/batched_kernel.h"
#include "integrator/reference.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {

constexpr int kMaxLoggedNonfinite = 5;

// The record of a sample when only the beauty's variance is asked for.
const AovSample kNoRecord{};

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
  // The arrays live per tile: declared per pixel, they were initialised for every pixel, which
  // a 1-spp render paid for each camera ray.
  Ray rays[kCameraChunk];
  SampleKey keys[kCameraChunk];
  Radiance radiance[kCameraChunk];
  bool firstOfPixel[kCameraChunk], lastOfPixel[kCameraChunk];
  // The pixel's state, at its first and last sample of the chunk (where it is read and kept).
  PixelEstimate* stateOf[kCameraChunk];
  // Written only when AOVs are asked for: cleared per sample, every sample would pay a store
  // of the whole record.
  UninitializedArray<AovSample, kCameraChunk> records;
  AovSample* recordOf[kCameraChunk];
  CameraSampling::Points cameraPoints;
  PixelEstimate pixel;  // the state of the pixel being sampled, kept when its last sample is in
  int count = 0;        // samples in the chunk
  const auto flush = [&]() {
    if (count == 0) return true;
    if (stopped(f.opt, pass)) return false;
    // The whole chunk's rays at once: its pixels' points share blocks of the sampler's lanes.
    f.cameraSampling.rays(keys, count, rays, cameraPoints);
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
        pixel = *stateOf[i];
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
        *stateOf[i] = pixel;
        if (aovs) pixelAovs.commit(f.aovSums, f.aovTables, key.px, key.py);
      }
    }
    count = 0;
    return true;
  };
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      if (!f.slots.holds(x, y)) continue;
      const size_t slot = f.slots.slot(x, y);
      if (!pass.sampled[slot]) continue;
      PixelEstimate* const state = &f.estimates[slot];
      const int64_t taken = state->samples();
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
          if (first) stateOf[count] = state;
          first = false;
          count += run;
          j += run;
        }
      if (!first) lastOfPixel[count - 1] = true, stateOf[count - 1] = state;
    }
  return flush();
}

// Runs tile(i, counters) for every tile on the scheduler, until a stop.
template <class RenderOneTile>
void forEachTile(const FrameContext& f, const PassContext& pass, TileWork& work,
                 RenderOneTile&& tile) {
  runTiles(work.tiles, work.threads, work.schedule, [&](size_t i) {
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
// renders: made per tile, its allocation, clearing and page faults would be paid again for
// every tile, a cost that grows as tiles shrink.
class ProductionTiles final : public TilePasses {
 public:
  ProductionTiles(const Scene& scene, const Accelerator& accel, int footprintSpp)
      : kernel_(scene, accel, kDefaultMinThroughput, footprintSpp) {}
  void render(const FrameContext& f, const PassContext& pass, TileWork& work) override {
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
class ReferenceTiles final : public TilePasses {
 public:
  ReferenceTiles(const Scene& scene, const Accelerator& accel, int footprintSpp)
      : integrator_(scene, accel, kDefaultMinThroughput, footprintSpp) {}
  void render(const FrameContext& f, const PassContext& pass, TileWork& work) override {
    forEachTile(f, pass, work, [&](size_t i, RayCounters& counters) {
      ReferenceShading shade{integrator_};
      return renderTilePass(f, pass, shade, work.tiles[i], counters);
    });
  }

 private:
  const ReferenceIntegrator integrator_;
};

}  // namespace

std::unique_ptr<TilePasses> makeTilePasses(IntegratorKind kind, const Scene& scene,
                                           const Accelerator& accel, int footprintSpp) {
  if (kind == IntegratorKind::Reference)
    return std::make_unique<ReferenceTiles>(scene, accel, footprintSpp);
  return std::make_unique<ProductionTiles>(scene, accel, footprintSpp);
}

}  // namespace glint
