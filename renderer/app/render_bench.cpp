#include "app/render_bench.h"

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "accel/ray_recorder.h"
#include "camera/camera.h"
#include "core/fp_env.h"
#include "core/sampler.h"
#include "core/seconds_since.h"
#include "render/pass_plan.h"
#include "render/render_job.h"

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

template <typename F>
double bestOf(int runs, F&& f) {
  double best = 1e300;
  for (int i = 0; i < runs; ++i) best = std::min(best, f());
  return best;
}

RenderResult render(const Scene& scene, const Accelerator& accel, int threads, int tileSize = 32) {
  RenderOptions opt;
  opt.threads = threads;
  opt.tileSize = tileSize;
  opt.progress = false;
  return renderScene(scene, accel, opt);
}

// Camera sampling alone: every camera ray the render makes, through the same CameraSampling,
// with nothing traced. The keys are packed as renderTilePass packs them, pass by pass (a
// uniform render's passes double the spp), each pixel's new half-0 samples then its half-1
// ones, several pixels to a chunk, so that the time is what the render pays for the same rays.
double samplingSeconds(const Scene& scene, int threads) {
  const RenderSettings& rs = scene.render;
  const PassPlan plan = PassPlan::make(rs.spp, rs.sampler, SamplingRequest{});
  const Camera camera(scene.cameraDesc, rs.width, rs.height);
  const Sampler sampler(plan.sampler, rs.spp, rs.seed);
  const CameraSampling cameraSampling(scene, camera);
  const PixelWindow window{0, rs.width, 0, rs.height};
  const auto tiles = makeTiles(window, effectiveTileSize(window, 32, threads));
  std::vector<float> sink(tiles.size());
  const auto start = Clock::now();
  runTiles(tiles, threads, [&](size_t t) {
    SampleKey keys[kCameraChunk];
    Ray rays[kCameraChunk];
    CameraSampling::Points points;
    float acc = 0;
    int count = 0;
    const auto flush = [&] {
      cameraSampling.rays(keys, count, rays, points);
      for (int i = 0; i < count; ++i) acc += rays[i].d.x + rays[i].time;
      count = 0;
    };
    for (size_t p = 0; p < plan.ends.size(); ++p) {
      const int taken = p == 0 ? 0 : plan.ends[p - 1], end = plan.ends[p];
      for (int y = tiles[t].y0; y < tiles[t].y1; ++y)
        for (int x = tiles[t].x0; x < tiles[t].x1; ++x) {
          const uint64_t pixelKey = sampler.pixelKey(x, y);
          for (int half = 0; half < 2; ++half)
            for (int j = halfSampleCount(taken, half); j < halfSampleCount(end, half); ++j) {
              if (count == kCameraChunk) flush();
              keys[count++] = SampleKey(&sampler, x, y, j, pixelKey, half);
            }
        }
      if (count > 0) flush();  // a tile's pass ends its last chunk
    }
    sink[t] = acc;
  });
  benchmark::DoNotOptimize(sink.data());
  return secondsSince(start);
}

// The film's share: every pixel written once, as the render does.
double filmSeconds(const Scene& scene) {
  const RenderSettings& rs = scene.render;
  Film film(rs.width, rs.height, {0, rs.width, 0, rs.height});
  const auto start = Clock::now();
  for (int y = 0; y < rs.height; ++y)
    for (int x = 0; x < rs.width; ++x) film.setPixel(x, y, x, y, 0, 1);
  return secondsSince(start);
}

double share(double part, double whole) { return whole > 0 ? 100 * part / whole : 0; }

}  // namespace

double replaySeconds(const Accelerator& accel, const std::vector<RecordedRay>& rays, int threads,
                     bool asTraced, int passes) {
  // Each query's first ray, and the rays it traces together: one by one, every ray is a query.
  std::vector<size_t> queries;
  size_t largest = 1;
  for (size_t i = 0, size; i < rays.size(); i += size) {
    size = asTraced ? std::max<uint32_t>(1, rays[i].query) : 1;
    queries.push_back(i);
    largest = std::max(largest, size);
  }
  tbb::task_arena arena(threads);
  const auto start = Clock::now();
  size_t hits = 0;
  arena.execute([&] {
    for (int pass = 0; pass < passes; ++pass)
      hits += tbb::parallel_reduce(
          tbb::blocked_range<size_t>(0, queries.size(), asTraced ? 1024 : 4096), size_t(0),
          [&](const tbb::blocked_range<size_t>& r, size_t n) {
            const FlushToZeroScope flushToZero;
            std::vector<Ray> batch(largest);
            std::vector<Hit> found(largest);
            std::unique_ptr<bool[]> blocked(new bool[largest]);
            for (size_t q = r.begin(); q != r.end(); ++q) {
              const RecordedRay* first = &rays[queries[q]];
              const size_t size = asTraced ? first->query : 1;
              if (size == 1) {
                n += first->occlusion ? accel.occluded(first->ray)
                                      : bool(accel.intersect(first->ray));
                continue;
              }
              for (size_t i = 0; i < size; ++i) batch[i] = first[i].ray;
              if (first->occlusion) {
                accel.occludedCoherent(batch.data(), blocked.get(), size);
                n += static_cast<size_t>(std::count(blocked.get(), blocked.get() + size, true));
              } else {
                accel.intersectCoherent(batch.data(), found.data(), size);
                n += static_cast<size_t>(std::count_if(found.begin(), found.begin() + long(size),
                                                       [](const Hit& h) { return bool(h); }));
              }
            }
            return n;
          },
          std::plus<>());
  });
  benchmark::DoNotOptimize(hits);
  return secondsSince(start) / passes;
}

double bestRenderSeconds(const Scene& scene, const Accelerator& accel, int threads, int tileSize,
                         int runs) {
  return bestOf(runs, [&] { return render(scene, accel, threads, tileSize).stats.seconds; });
}

int64_t sceneGeometryBytes(const Scene& scene, const EmbreeAccel& embree) {
  int64_t bytes = embree.bytes();
  for (const TriangleMesh& m : scene.meshes) {
    bytes += int64_t(m.positions.capacity() * sizeof(Vec3f) + m.indices.capacity() * 4);
    for (const auto& key : m.positionKeys) bytes += int64_t(key.capacity() * sizeof(Vec3f));
  }
  return bytes;
}

nlohmann::json benchWholeRender(const Scene& scene, const EmbreeAccel& embree,
                                const RenderBenchOptions& opt) {
  nlohmann::json j;
  const int n = opt.threads;
  // One render first: its ray count sizes the recording below, and it counts as the first of
  // the timed runs.
  RenderStats stats = render(scene, embree, n).stats;
  double seconds = stats.seconds;

  // The Embree limit: the render's rays, recorded in an untimed render (a fixed subset of
  // about kMaxRecorded, one query in `stride` of each thread so the mix of kinds is kept),
  // replayed through Embree alone and scaled to the whole render.
  constexpr uint64_t kMaxRecorded = 1 << 21;
  const uint64_t stride =
      std::max<uint64_t>(1, (stats.rays.total() + kMaxRecorded - 1) / kMaxRecorded);
  RayRecorder recorder(embree, stride);
  render(scene, recorder, n);
  const std::vector<RecordedRay> recorded = recorder.take();
  // Each replay repeats the recorded rays for about a render's duration, so that a short
  // replay cannot fall into a quiet moment of a shared machine that the render did not see.
  const int passes =
      std::max(1, static_cast<int>(seconds / replaySeconds(embree, recorded, n, false, 1)));

  // Interleave renders and replays so that drift hits them all alike.
  double replay = 1e300, traced = 1e300;
  for (int run = 0; run < opt.runs; ++run) {
    if (run > 0) {
      const RenderResult r = render(scene, embree, n);
      seconds = std::min(seconds, r.stats.seconds);
      stats = r.stats;
    }
    replay = std::min(replay, replaySeconds(embree, recorded, n, false, passes));
    traced = std::min(traced, replaySeconds(embree, recorded, n, true, passes));
  }
  const RayCounters& rays = stats.rays;
  const double mrays = double(rays.total()) / seconds * 1e-6;
  std::printf("\nwhole render   %d threads, best of %d: %.3f s\n", n, opt.runs, seconds);
  std::printf("rays           %llu: camera %llu, shadow %llu, reflection %llu, refraction %llu\n",
              (unsigned long long)rays.total(), (unsigned long long)rays.camera,
              (unsigned long long)rays.shadow, (unsigned long long)rays.reflection,
              (unsigned long long)rays.refraction);
  std::printf("rate           %.2f Mrays/s, %.2f Mrays/s per thread\n", mrays, mrays / n);
  const double replayRate = double(recorded.size()) / replay;
  const double ratio = double(rays.total()) / replayRate / seconds;
  std::printf(
      "embree limit   %zu of the rays (one query in %llu) replayed through Embree alone, one by "
      "one, at %.2f Mrays/s: ratio %.3f\n",
      recorded.size(), (unsigned long long)stride, replayRate * 1e-6, ratio);
  // The traversal the render pays: its coherent batches as packets. Faster than one by one
  // (the packets, and Glint's lane-parallel sphere and quad tests inside them), so it, not the
  // limit above, is the traversal share of the split.
  const double tracedRate = double(recorded.size()) / traced;
  const double traversal = double(rays.total()) / tracedRate;
  std::printf(
      "as traced      the same queries as the render made them (batches as packets): "
      "%.2f Mrays/s, %.2fx one by one\n",
      tracedRate * 1e-6, tracedRate / replayRate);

  const double sampling = bestOf(opt.runs, [&] { return samplingSeconds(scene, n); });
  const double film = bestOf(opt.runs, [&] { return filmSeconds(scene); });
  const double rest = std::max(0.0, seconds - traversal - sampling - film);
  std::printf(
      "time split     traversal %.3f s (%.0f%%), camera sampling %.3f s (%.0f%%), film %.4f s "
      "(%.1f%%), shading and the rest %.3f s (%.0f%%)\n",
      traversal, share(traversal, seconds), sampling, share(sampling, seconds), film,
      share(film, seconds), rest, share(rest, seconds));

  j["threads"] = n;
  j["render_seconds"] = seconds;
  j["rays"] = {{"camera", rays.camera},
               {"shadow", rays.shadow},
               {"reflection", rays.reflection},
               {"refraction", rays.refraction}};
  j["mrays_per_s"] = mrays;
  j["mrays_per_s_per_thread"] = mrays / n;
  j["embree_limit_ratio"] = ratio;
  j["embree_replay_mrays_per_s"] = replayRate * 1e-6;
  j["as_traced_replay_mrays_per_s"] = tracedRate * 1e-6;
  j["time_split_seconds"] = {{"traversal", traversal},
                             {"camera_sampling", sampling},
                             {"film", film},
                             {"shading_and_rest", rest}};
  return j;
}

}  // namespace glint
