// `glint bench`: ray rates of the intersection backends on a scene's own camera, shadow and
// random rays, single-threaded and on all threads, timed by Google Benchmark.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "accel/accelerator.h"
#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/reference_bvh.h"
#include "app/accel_options.h"
#include "app/commands.h"
#include "app/intersection_share.h"
#include "app/procedural_scene.h"
#include "app/render_bench.h"
#include "app/scene_source.h"
#include "app/structure_study.h"
#include "camera/camera.h"
#include "core/error.h"
#include "core/fp_env.h"
#include "core/hash.h"
#include "core/memory.h"
#include "core/seconds_since.h"
#include "film/atomic_file.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {

struct BenchArgs {
  std::string scenePath;
  std::string accels = "embree,bvh";
  AccelOptions accelOptions;
  size_t procedural = 0;
  int threads = 0;
  int randomRays = 1 << 20;
  double minSeconds = 0.5;
  int renderRuns = 3;
  bool structures = false;
  bool intersectionShare = false;
  int width = 0, height = 0;  // 0: the scene's
  std::string json;
};

struct RaySets {
  std::vector<Ray> camera, shadow, random;
};

// Camera rays through every pixel centre; shadow rays from their hits towards the first light
// (or straight up when there is none; none without `accel`); random rays as in `glint validate`.
RaySets makeRays(const Scene& scene, const Accelerator* accel, int randomCount) {
  RaySets sets;
  const Camera cam(scene.cameraDesc, scene.render.width, scene.render.height);
  for (int y = 0; y < scene.render.height; ++y)
    for (int x = 0; x < scene.render.width; ++x)
      sets.camera.push_back(cam.generateRay(float(x) + 0.5f, float(y) + 0.5f));
  for (size_t i = 0; accel && i < sets.camera.size(); ++i) {
    const Ray& r = sets.camera[i];
    const Hit h = accel->intersect(r);
    if (!h) continue;
    const ShadingPoint sp = scene.shadingPoint(r, h);
    const Vec3f target = scene.lights.empty()
                             ? sp.p + Vec3f{0, 1e3f, 0}
                             : sampleLight(scene.lights[0], sp.p, sp.ng, {0.5f, 0.5f}).target;
    sets.shadow.push_back(spawnShadowRay(sp, true, target, 0, 0));
  }
  const Bounds3f b = randomRayOrigins(scene);
  for (int i = 0; i < randomCount; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(99, i, k)); };
    const float z = 1 - 2 * u(3), phi = 2 * kPi * u(4), s = std::sqrt(std::max(0.0f, 1 - z * z));
    sets.random.push_back({b.lo + mul(b.diagonal(), Vec3f{u(0), u(1), u(2)}),
                           {s * std::cos(phi), s * std::sin(phi), z}});
  }
  return sets;
}

// Collects Google Benchmark's items-per-second by benchmark name.
class RateCollector : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      const auto it = r.counters.find("items_per_second");
      if (it != r.counters.end()) rates[r.run_name.function_name] = it->second.value;
    }
  }
  std::map<std::string, double> rates;
};

int runBench(const BenchArgs& a) {
  checkCommandOutputs({{"--json", a.json}});
  // Before the scene loads: a misspelt backend is known at once. A backend named twice would
  // be timed twice and its figures reported under one name.
  std::vector<AccelKind> kinds;
  std::stringstream list(a.accels);
  for (std::string name; std::getline(list, name, ',');) {
    AccelKind k;
    if (!parseAccelKind(name, k)) throw UsageError("--accel: unknown backend " + inQuotes(name));
    if (std::find(kinds.begin(), kinds.end(), k) != kinds.end())
      throw UsageError("--accel: " + inQuotes(name) + " is named twice");
    kinds.push_back(k);
  }
  if (kinds.empty()) throw UsageError("--accel: name at least one backend");
  const auto loadStart = std::chrono::steady_clock::now();
  Scene scene = a.procedural ? makeProceduralScene(a.procedural) : loadSceneOrDefault(a.scenePath);
  if (a.width > 0) scene.render.width = a.width;
  if (a.height > 0) scene.render.height = a.height;
  const double loadSeconds = secondsSince(loadStart);
  if (a.structures) {
    const RaySets rays = makeRays(scene, nullptr, a.randomRays);
    nlohmann::json j = studyStructures(scene, kinds, rays.camera, rays.random, a.accelOptions);
    j["scene"] = scene.sourcePath;
    j["load_seconds"] = loadSeconds;
    if (!a.json.empty()) writeTextFileAtomically(a.json, j.dump(2) + "\n");
    return kExitOk;
  }
  if (a.intersectionShare) {
    nlohmann::json j =
        studyIntersectionShare(scene, kinds, std::max(1, a.renderRuns), a.accelOptions);
    j["scene"] = scene.sourcePath;
    j["width"] = scene.render.width;
    j["height"] = scene.render.height;
    if (!a.json.empty()) writeTextFileAtomically(a.json, j.dump(2) + "\n");
    return kExitOk;
  }
  const int allThreads = threadCount(a.threads);
  std::printf("scene          %s, %zu triangles\n", scene.sourcePath.c_str(),
              scene.triangleCount());

  const EmbreeAccel embree(scene);
  // Memory before any whole render (the ray recording would dominate the peak): a
  // ~1M-triangle scene should need ≤ 100 B per triangle, Embree's BVH included.
  const int64_t geometry = sceneGeometryBytes(scene, embree);
  const size_t tris = scene.triangleCount();
  std::printf("memory         scene geometry + Embree %.1f MB", double(geometry) * 1e-6);
  if (tris > 0) std::printf(" = %.1f B/triangle", double(geometry) / double(tris));
  std::printf(", peak resident %.1f MB; load %.3f s, Embree build %.3f s\n",
              double(peakResidentBytes()) * 1e-6, loadSeconds, embree.buildSeconds());
  nlohmann::json memory;
  memory["bytes_per_triangle"] =
      tris > 0 ? nlohmann::json(double(geometry) / double(tris)) : nlohmann::json();
  memory["peak_resident_bytes"] = peakResidentBytes();
  memory["load_seconds"] = loadSeconds;
  memory["build_seconds"] = embree.buildSeconds();

  std::vector<std::unique_ptr<Accelerator>> owned;
  std::vector<const Accelerator*> accels;
  for (AccelKind k : kinds) {
    if (k != AccelKind::Embree) owned.push_back(makeAccelerator(k, scene, a.accelOptions));
    accels.push_back(k == AccelKind::Embree ? &embree : owned.back().get());
  }
  const RaySets rays = makeRays(scene, accels[0], a.randomRays);
  struct Set {
    const char* name;
    const std::vector<Ray>* rays;
    bool occlusion;
  };
  const Set sets[] = {{"camera", &rays.camera, false},
                      {"shadow", &rays.shadow, true},
                      {"random", &rays.random, false}};
  for (const Accelerator* accel : accels)
    for (const Set& set : sets)
      for (int threads : {1, allThreads}) {
        const std::string name =
            std::string(accel->name()) + "/" + set.name + "/threads:" + std::to_string(threads);
        const Accelerator* acc = accel;
        benchmark::RegisterBenchmark(
            name.c_str(),
            [acc, set, threads](benchmark::State& state) {
              tbb::task_arena arena(threads);
              size_t hits = 0;
              for (auto _ : state) {
                arena.execute([&] {
                  hits += tbb::parallel_reduce(
                      tbb::blocked_range<size_t>(0, set.rays->size(), 4096), size_t(0),
                      [&](const tbb::blocked_range<size_t>& r, size_t n) {
                        const FlushToZeroScope flushToZero;
                        for (size_t i = r.begin(); i != r.end(); ++i)
                          n += set.occlusion ? acc->occluded((*set.rays)[i])
                                             : bool(acc->intersect((*set.rays)[i]));
                        return n;
                      },
                      std::plus<>());
                });
              }
              benchmark::DoNotOptimize(hits);
              state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(set.rays->size()));
            })
            ->MinTime(0.1)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
  // Camera rays and shadow rays as coherent streams (EmbreeAccel's intersectCoherent and
  // occludedCoherent, rtcIntersect1M with packets inside Embree) against one by one: the same
  // rays and answers, so the ratio says whether packets pay for this scene.
  for (const bool shadow : {false, true})
    for (int threads : {1, allThreads}) {
      const std::string name = std::string("embree/") + (shadow ? "shadow" : "camera") +
                               "-stream/threads:" + std::to_string(threads);
      const std::vector<Ray>* set = shadow ? &rays.shadow : &rays.camera;
      const EmbreeAccel* acc = &embree;
      benchmark::RegisterBenchmark(
          name.c_str(),
          [acc, set, threads, shadow](benchmark::State& state) {
            tbb::task_arena arena(threads);
            std::vector<Hit> hits(set->size());
            std::unique_ptr<bool[]> blocked(new bool[set->size()]);
            for (auto _ : state)
              arena.execute([&] {
                tbb::parallel_for(tbb::blocked_range<size_t>(0, set->size(), 4096),
                                  [&](const tbb::blocked_range<size_t>& r) {
                                    const FlushToZeroScope flushToZero;
                                    if (shadow)
                                      acc->occludedCoherent(set->data() + r.begin(),
                                                            blocked.get() + r.begin(), r.size());
                                    else
                                      acc->intersectCoherent(set->data() + r.begin(),
                                                             hits.data() + r.begin(), r.size());
                                  });
              });
            benchmark::DoNotOptimize(hits.data());
            benchmark::DoNotOptimize(blocked.get());
            state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(set->size()));
          })
          ->MinTime(0.1)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  RateCollector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::ClearRegisteredBenchmarks();

  nlohmann::json j;
  std::printf("%-8s %-7s %14s %14s %10s\n", "backend", "rays", "1 thread", "all threads",
              "vs embree");
  for (const auto& accel : accels)
    for (const Set& set : sets) {
      const auto rate = [&](const std::string& acc, int t) {
        return collector.rates[acc + "/" + set.name + "/threads:" + std::to_string(t)] * 1e-6;
      };
      const std::string n(accel->name());
      const double one = rate(n, 1), all = rate(n, allThreads), base = rate("embree", 1);
      std::printf("%-8s %-7s %9.2f Mr/s %9.2f Mr/s %9.2fx\n", n.c_str(), set.name, one, all,
                  base > 0 ? one / base : 0.0);
      j["backends"][n][set.name] = {
          {"mrays_per_s_1_thread", one}, {"mrays_per_s_all_threads", all}, {"threads", allThreads}};
    }
  for (const char* kind : {"camera", "shadow"}) {
    const auto rate = [&](const std::string& set, int t) {
      return collector.rates["embree/" + set + "/threads:" + std::to_string(t)] * 1e-6;
    };
    const std::string stream = std::string(kind) + "-stream";
    const double one = rate(stream, 1), all = rate(stream, allThreads), single = rate(kind, 1);
    std::printf("%-8s %-7s %9.2f Mr/s %9.2f Mr/s %9.2fx  (coherent stream vs one by one)\n",
                "embree", (std::string(kind).substr(0, 3) + "-1M").c_str(), one, all,
                single > 0 ? one / single : 0.0);
    j["backends"]["embree"][std::string(kind) + "_stream"] = {
        {"mrays_per_s_1_thread", one}, {"mrays_per_s_all_threads", all}, {"threads", allThreads}};
  }
  // The three reference-BVH builds side by side (seed 000 §12.3.2 against Wald's binned SAH).
  std::printf("\n%-9s %9s %9s %8s %10s %12s\n", "bvh build", "seconds", "nodes", "depth",
              "SAH cost", "random Mr/s");
  for (BvhSplit split : {BvhSplit::Sah, BvhSplit::Median, BvhSplit::Midpoint}) {
    const ReferenceBvh bvh(scene, split);
    const auto start = std::chrono::steady_clock::now();
    size_t hits = 0;
    for (const Ray& r : rays.random) hits += bool(bvh.intersect(r));
    benchmark::DoNotOptimize(hits);
    const double secs = secondsSince(start);
    const BvhStats& st = bvh.stats();
    const double rate = double(rays.random.size()) / secs * 1e-6;
    std::printf("%-9s %9.3f %9zu %8zu %10.2f %12.2f\n", std::string(bvhSplitName(split)).c_str(),
                st.buildSeconds, st.nodes, st.maxDepth, st.sahCost, rate);
    j["bvh_builds"][std::string(bvhSplitName(split))] = {{"build_seconds", st.buildSeconds},
                                                         {"nodes", st.nodes},
                                                         {"sah_cost", st.sahCost},
                                                         {"random_mrays_per_s_1_thread", rate}};
  }
  // Whole renders through the tile scheduler: parallel efficiency 1 → N threads, and tile
  // sizes (each the best of `renderRuns` runs, since the machine is shared).
  nlohmann::json whole;
  if (a.renderRuns > 0) {
    whole = benchWholeRender(scene, embree, {allThreads, a.renderRuns});
    whole.update(memory);
    const auto timeRender = [&](int threads, int tile) {
      return bestRenderSeconds(scene, embree, threads, tile, a.renderRuns);
    };
    const double t1 = timeRender(1, 32), tn = timeRender(allThreads, 32);
    const double efficiency = t1 / (allThreads * tn);
    std::printf("\nrender         1 thread %.3f s, %d threads %.3f s: parallel efficiency %.3f\n",
                t1, allThreads, tn, efficiency);
    j["parallel_efficiency"] = efficiency;
    j["render_seconds"] = {{"1_thread", t1}, {"all_threads", tn}};
    std::printf("tile size     ");
    for (int tile : {8, 16, 32, 64}) {
      const double t = timeRender(allThreads, tile);
      std::printf(" %d: %.3f s ", tile, t);
      j["tile_seconds"][std::to_string(tile)] = t;
    }
    std::printf("\n");
  }
  j["scene"] = scene.sourcePath;
  j["triangles"] = scene.triangleCount();
  j["whole_render"] = whole;
  // The keys CLI.md promises, null where not measured (--render-runs 0).
  for (const char* key : {"mrays_per_s", "embree_limit_ratio", "bytes_per_triangle"})
    j[key] = whole.contains(key) ? whole[key] : nlohmann::json();
  if (!j.contains("parallel_efficiency")) j["parallel_efficiency"] = nullptr;
  if (!a.json.empty()) {
    writeTextFileAtomically(a.json, j.dump(2) + "\n");
  }
  return kExitOk;
}

}  // namespace

CommandRunner addBenchCommand(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand("bench", "Ray rates of the intersection backends");
  cmd->add_option("scene", args->scenePath, sceneArgumentHelp())->check(CLI::ExistingFile);
  cmd->add_option("--accel", args->accels,
                  "Comma-separated backends (embree, bvh, brute, grid, octree, kdtree, "
                  "octree-generate-and-test, rayclass, coherence, spheres)");
  addAccelOptions(*cmd, args->accelOptions);
  // A heightfield beyond 2^28 triangles would not fit this machine's memory (80 B each).
  cmd->add_option("--procedural", args->procedural,
                  "Benchmark a generated heightfield of about this many triangles instead")
      ->check(wholeNumberUpTo(uint64_t{1} << 28));
  cmd->add_option("--threads", args->threads, "Threads for the all-threads runs (default: all)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--random-rays", args->randomRays, "Random rays per pass")
      ->check(CLI::Range(1, 1 << 26));
  cmd->add_option("--render-runs", args->renderRuns,
                  "Whole renders per configuration for efficiency and tile sizes (0: skip)")
      ->check(CLI::Range(0, 100));
  cmd->add_flag("--structures", args->structures,
                "Only the study of the acceleration structures: build time, memory and one "
                "thread's time per camera and random ray for each --accel (docs/acceleration.md)");
  cmd->add_flag("--intersection-share", args->intersectionShare,
                "Only the share of one thread's render time spent in intersection, for each "
                "--accel: the render's rays replayed through the backend alone, best of "
                "--render-runs (docs/acceleration.md)")
      ->excludes("--structures");
  cmd->add_option("--width", args->width, "Image width instead of the scene's")
      ->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--height", args->height, "Image height instead of the scene's")
      ->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--json", args->json, "Write the figures as JSON")->check(nonEmpty());
  return [args] { return runBench(*args); };
}

}  // namespace glint
