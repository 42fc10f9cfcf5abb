#include "app/structure_study.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "accel/embree_accel.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/ray_classification.h"
#include "accel/ray_coherence.h"
#include "accel/reference_bvh.h"
#include "accel/sphere_hierarchy.h"
#include "accel/two_level.h"
#include "accel/uniform_grid.h"
#include "core/fp_env.h"
#include "core/seconds_since.h"

namespace glint {

namespace {

// Bytes the structure holds beside the scene (its nodes, cells, references and boxes).
size_t structureBytes(const Accelerator& accel) {
  if (const auto* e = dynamic_cast<const EmbreeAccel*>(&accel)) return size_t(e->bytes());
  if (const auto* b = dynamic_cast<const ReferenceBvh*>(&accel)) return b->stats().bytes;
  if (const auto* g = dynamic_cast<const UniformGrid*>(&accel)) return g->stats().bytes;
  if (const auto* o = dynamic_cast<const Octree*>(&accel)) return o->stats().bytes;
  if (const auto* k = dynamic_cast<const KdTree*>(&accel)) return k->stats().bytes;
  if (const auto* r = dynamic_cast<const RayClassification*>(&accel))
    return r->stats().fixedBytes + r->stats().lazyBytes;
  if (const auto* c = dynamic_cast<const RayCoherence*>(&accel)) return c->stats().bytes;
  if (const auto* s = dynamic_cast<const SphereHierarchy*>(&accel)) return s->stats().bytes;
  return 0;
}

// Nanoseconds per closest-hit query on one thread: the best of three passes (the machine is
// shared), or of one when a pass takes more than 10 s; and the first pass's, which for a
// structure built lazily (rayclass) includes the building.
struct RayTimes {
  double best = 0, first = 0;
};
RayTimes nanosecondsPerRay(const Accelerator& accel, const std::vector<Ray>& rays) {
  if (rays.empty()) return {};
  const FlushToZeroScope flushToZero;
  double best = kInfinity, first = 0;
  for (int pass = 0; pass < 3; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    size_t hits = 0;
    for (const Ray& r : rays) hits += bool(accel.intersect(r));
    const double s = secondsSince(start);
    benchmark::DoNotOptimize(hits);
    if (pass == 0) first = s;
    best = std::min(best, s);
    if (s > 10) break;
  }
  return {best / double(rays.size()) * 1e9, first / double(rays.size()) * 1e9};
}

// What ray classification has made lazily (accel/ray_classification.h), as a JSON object.
nlohmann::json lazyCells(const RayClassStats& s) {
  return {{"cells", s.cells},
          {"references", s.references},
          {"bytes", s.lazyBytes},
          {"cap_bytes", s.capBytes}};
}

// Mean nodes or cells visited and primitives tested per closest-hit query, for a structure whose
// traversal Glint can count (accel/two_level.h); null for Embree.
nlohmann::json countsPerRay(const Accelerator& accel, const std::vector<Ray>& rays) {
  const auto* counting = dynamic_cast<const CountingTraversal*>(&accel);
  if (!counting || rays.empty()) return {{"steps", nullptr}, {"tests", nullptr}};
  TraversalCounts counts;
  for (const Ray& r : rays) counting->intersectCounting(r, counts);
  const double n = double(rays.size());
  return {{"steps", double(counts.steps) / n}, {"tests", double(counts.tests) / n}};
}

// What the study records of a subdivision beside time and memory: references per primitive,
// and for the octree its leaves that no surface meets, empty and full (seed 002 §9.2.2).
nlohmann::json subdivisionFigures(const Accelerator& accel) {
  if (const auto* o = dynamic_cast<const Octree*>(&accel))
    return {{"references_per_primitive", o->stats().referencesPerPrimitive()},
            {"leaves", o->stats().leaves},
            {"empty_leaves", o->stats().emptyLeaves},
            {"full_leaves", o->stats().fullLeaves}};
  if (const auto* g = dynamic_cast<const UniformGrid*>(&accel))
    return {{"references_per_primitive",
             g->stats().primitives ? double(g->stats().references) / double(g->stats().primitives)
                                   : 0.0}};
  return nlohmann::json::object();
}

std::string oneDecimal(const nlohmann::json& value) {
  if (value.is_null()) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value.get<double>());
  return text;
}

}  // namespace

nlohmann::json studyStructures(const Scene& scene, const std::vector<AccelKind>& kinds,
                               const std::vector<Ray>& cameraRays,
                               const std::vector<Ray>& randomRays, const AccelOptions& options) {
  nlohmann::json j;
  j["primitives"] = scene.primitiveCount();
  std::printf("%-8s %10s %10s %14s %14s %22s %22s\n", "backend", "build s", "MiB", "camera ns/ray",
              "random ns/ray", "camera steps/tests", "random steps/tests");
  for (AccelKind kind : kinds) {
    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<Accelerator> accel = makeAccelerator(kind, scene, options);
    const double build = secondsSince(start);
    const auto* rayclass = dynamic_cast<const RayClassification*>(accel.get());
    const RayTimes camera = nanosecondsPerRay(*accel, cameraRays);
    const nlohmann::json afterCamera = rayclass ? lazyCells(rayclass->stats()) : nlohmann::json();
    const RayTimes random = nanosecondsPerRay(*accel, randomRays);
    const nlohmann::json afterRandom = rayclass ? lazyCells(rayclass->stats()) : nlohmann::json();
    const size_t bytes = structureBytes(*accel);  // after the rays: rayclass builds while tracing
    const nlohmann::json cameraCounts = countsPerRay(*accel, cameraRays);
    const nlohmann::json randomCounts = countsPerRay(*accel, randomRays);
    const auto pair = [](const nlohmann::json& c) {
      return oneDecimal(c["steps"]) + " / " + oneDecimal(c["tests"]);
    };
    std::printf("%-8s %10.4f %10.2f %14.1f %14.1f %22s %22s\n", std::string(accel->name()).c_str(),
                build, double(bytes) / (1 << 20), camera.best, random.best,
                pair(cameraCounts).c_str(), pair(randomCounts).c_str());
    if (rayclass)
      std::printf(
          "%-8s lazily made: %zu cells, %.2f MiB after the camera rays (first pass %.1f "
          "ns/ray); %zu cells, %.2f MiB after the random rays too (first pass %.1f "
          "ns/ray); cap %.1f MiB\n",
          "", afterCamera["cells"].get<size_t>(), afterCamera["bytes"].get<double>() / (1 << 20),
          camera.first, afterRandom["cells"].get<size_t>(),
          afterRandom["bytes"].get<double>() / (1 << 20), random.first,
          double(rayclass->stats().capBytes) / (1 << 20));
    std::fflush(stdout);
    j["structures"][std::string(accel->name())] = {{"build_seconds", build},
                                                   {"bytes", bytes},
                                                   {"camera_ns_per_ray", camera.best},
                                                   {"random_ns_per_ray", random.best},
                                                   {"camera_first_pass_ns_per_ray", camera.first},
                                                   {"random_first_pass_ns_per_ray", random.first},
                                                   {"camera_steps_per_ray", cameraCounts["steps"]},
                                                   {"camera_tests_per_ray", cameraCounts["tests"]},
                                                   {"random_steps_per_ray", randomCounts["steps"]},
                                                   {"random_tests_per_ray", randomCounts["tests"]}};
    if (rayclass)
      j["structures"][std::string(accel->name())]["lazy"] = {{"after_camera", afterCamera},
                                                             {"after_random", afterRandom}};
    j["structures"][std::string(accel->name())].update(subdivisionFigures(*accel));
    // Ray coherence's preprocessing is O(m·n) in the seed: m origins, n objects.
    if (const auto* c = dynamic_cast<const RayCoherence*>(accel.get()))
      j["structures"][std::string(accel->name())].update({{"origins", c->stats().origins},
                                                          {"rows", c->stats().rows},
                                                          {"objects", c->stats().objects},
                                                          {"pairs", c->stats().pairs},
                                                          {"references", c->stats().references}});
  }
  return j;
}

}  // namespace glint
