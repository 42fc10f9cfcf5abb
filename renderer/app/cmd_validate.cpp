// `glint validate`: renders the scene's own rays (camera, reflection, refraction, shadow) and
// N random rays through Embree, the reference BVH, the uniform grid, the octree, the k-d tree,
// ray classification, the sphere hierarchy and (for small scenes) brute force, and reports how
// well they agree, hit by hit.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "accel/brute_force.h"
#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/origin_rays.h"
#include "accel/ray_classification.h"
#include "accel/ray_coherence.h"
#include "accel/reference_bvh.h"
#include "accel/sphere_hierarchy.h"
#include "accel/uniform_grid.h"
#include "app/accel_options.h"
#include "app/commands.h"
#include "app/option_arity.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "core/memory.h"
#include "film/atomic_file.h"
#include "render/render_job.h"

namespace glint {

namespace {

struct ValidateArgs {
  std::string scenePath;
  int rays = 100000;
  uint64_t seed = 1;
  int spp = 1;
  double minAgreement = 1 - 1e-6;
  std::string json;
  std::vector<std::string> ray;  // --ray's nine numbers
  bool occludedRay = false;
  bool noBrute = false;
  AccelOptions accelOptions;
};

// Brute force is O(N) per ray: used when the scene has at most this many primitives.
constexpr size_t kBruteForceLimit = 5000;

int runValidate(const ValidateArgs& a) {
  checkOutputPaths({{"--json", a.json}});
  Scene scene = loadSceneOrDefault(a.scenePath);
  const EmbreeAccel embree(scene);
  const ReferenceBvh bvh(scene);
  const UniformGrid grid(scene);
  const Octree octree(scene);
  const Octree octreeGenerateAndTest(scene, 0, Octree::Walk::GenerateAndTest);
  const KdTree kdtree(scene);
  const RayClassification rayclass(scene, a.accelOptions.rayclass);
  const RayCoherence coherence(scene);
  const SphereHierarchy spheres(scene);
  std::unique_ptr<BruteForce> brute;
  if (!a.noBrute && scene.primitiveCount() <= kBruteForceLimit)
    brute = std::make_unique<BruteForce>(scene);
  std::vector<const Accelerator*> others{&bvh, &grid, &octree, &kdtree};
  others.push_back(&octreeGenerateAndTest);
  others.push_back(&rayclass);
  others.push_back(&coherence);
  others.push_back(&spheres);
  if (brute) others.push_back(brute.get());

  if (!a.ray.empty()) {  // reproduce one ray from a report line
    Ray r;
    std::string text;
    for (const std::string& v : a.ray) text += v + " ";
    if (!parseRay(text, r))
      throw UsageError("--ray: expected 9 numbers: ox oy oz dx dy dz tmin tmax time");
    if (const std::string why = rayProblem(r); !why.empty()) throw UsageError("--ray: " + why);
    std::printf("ray %s\n", formatRay(r).c_str());
    for (const Accelerator* acc : std::vector<const Accelerator*>{
             &embree, &bvh, &grid, &octree, &kdtree, &octreeGenerateAndTest, &rayclass, &coherence,
             &spheres, brute.get()})
      if (acc)
        std::printf("  %-24s %s\n", std::string(acc->name()).c_str(),
                    a.occludedRay ? (acc->occluded(r) ? "occluded" : "clear")
                                  : formatHit(acc->intersect(r)).c_str());
    return kExitOk;
  }

  // Every comparison where both backends hit keeps its |Δt| (CrossCheckStats::relDt), and the
  // 99.9th percentile sorts a copy: checked against the memory there is before any ray is cast.
  const double needed = 2.0 * double(a.rays) * double(others.size()) * double(sizeof(float));
  if (const uint64_t available = availableMemoryBytes();
      available != 0 && needed > double(available))
    throw UsageError("--rays " + std::to_string(a.rays) + ": comparing " +
                     std::to_string(others.size()) + " backends with Embree keeps about " +
                     gigabytes(needed) + " of distances; " + gigabytes(double(available)) +
                     " is available: cast fewer rays (or several runs with other --seed values)");
  const CrossCheck check(embree, others);
  // --spp 0: random rays only. The renderer needs at least one sample (a sampler of 0 samples
  // divided by zero: SIGFPE, found by the CLI number table, tests/app/cli_numbers_test.cpp).
  if (a.spp > 0) {
    scene.render.spp = a.spp;
    RenderOptions opt;
    opt.threads = 1;  // reproducible statistics and first disagreements
    opt.progress = false;
    renderScene(scene, check, opt);
  }
  castRandomRays(scene, check, a.rays, a.seed);
  castOriginRays(scene, embree, check, a.rays / 4, a.seed);

  const CrossCheckStats& st = check.stats();
  const BvhStats& bs = bvh.stats();
  std::printf(
      "backends       embree, bvh, grid, octree, kdtree, octree-generate-and-test, rayclass, "
      "coherence, spheres%s\n",
      brute ? ", brute" : " (brute force skipped: scene too large)");
  std::printf(
      "queries        %llu closest-hit, %llu occlusion (scene rays at %d spp + %d random + "
      "%d samples of rays from origins)\n",
      (unsigned long long)st.rays, (unsigned long long)st.occlusionRays, a.spp, a.rays, a.rays / 4);
  std::printf("hit/miss       %.9f agreement\n", st.hitAgreement());
  std::printf("primitive      %.9f agreement (ties within %.0e count as agreement)\n",
              st.primAgreement(), double(CrossCheck::kTieTolerance));
  std::printf("occlusion      %.9f agreement\n", st.occlusionAgreement());
  std::printf("origin ties    %llu (a hit within %.0e of the ray's origin against a miss)\n",
              (unsigned long long)st.originTies, double(CrossCheck::kOriginTolerance));
  std::printf("|dt|/max(1,t)  max %.3g, 99.9th percentile %.3g\n", double(st.maxRelDt()),
              double(st.quantileRelDt(0.999)));
  std::printf("embree build   %.3f s, %.1f MiB\n", embree.buildSeconds(),
              double(embree.bytes()) / (1 << 20));
  std::printf(
      "bvh build      %.3f s, %zu nodes, %zu leaves, %.2f prims/leaf, depth %zu, "
      "SAH cost %.2f, %.1f MiB\n",
      bs.buildSeconds, bs.nodes, bs.leaves, bs.primitivesPerLeaf(), bs.maxDepth, bs.sahCost,
      double(bs.bytes) / (1 << 20));
  const GridStats& gs = grid.stats();
  std::printf("grid build     %.3f s, %zu cells, %zu references (%.2f per primitive), %.1f MiB\n",
              gs.buildSeconds, gs.cells, gs.references,
              gs.primitives ? double(gs.references) / double(gs.primitives) : 0.0,
              double(gs.bytes) / (1 << 20));
  for (const auto& [label, ts] :
       {std::pair{"octree build ", &octree.stats()}, std::pair{"kdtree build ", &kdtree.stats()},
        std::pair{"spheres build", &spheres.stats()}})
    std::printf(
        "%s  %.3f s, %zu nodes, %zu leaves, depth %zu, %zu references (%.2f per "
        "primitive), %.1f MiB\n",
        label, ts->buildSeconds, ts->nodes, ts->leaves, ts->maxDepth, ts->references,
        ts->referencesPerPrimitive(), double(ts->bytes) / (1 << 20));
  const RayClassStats rs = rayclass.stats();
  std::printf(
      "rayclass cells %zu made while tracing (n_min %u, w_min %g), %zu references (%.2f per "
      "primitive), %.1f MiB of a cap of %.1f MiB, %.1f MiB besides\n",
      rs.cells, a.accelOptions.rayclass.nMin, a.accelOptions.rayclass.wMin, rs.references,
      rs.primitives ? double(rs.references) / double(rs.primitives) : 0.0,
      double(rs.lazyBytes) / (1 << 20), double(rs.capBytes) / (1 << 20),
      double(rs.fixedBytes) / (1 << 20));
  const CoherenceStats& cs = coherence.stats();
  std::printf(
      "coherence build %.3f s, %zu origins (%zu with a row), %zu objects, %zu classes, %zu "
      "references, %.1f MiB\n",
      cs.buildSeconds, cs.origins, cs.rows, cs.objects, cs.classes, cs.references,
      double(cs.bytes) / (1 << 20));
  if (!st.firstDisagreements.empty()) {
    std::printf("first disagreements (reproduce with glint validate SCENE --ray ...):\n");
    for (const auto& line : st.firstDisagreements) std::printf("  %s\n", line.c_str());
  }
  if (!a.json.empty()) {
    nlohmann::json j;
    j["rays"] = st.rays;
    j["occlusion_rays"] = st.occlusionRays;
    j["hit_agreement"] = st.hitAgreement();
    j["prim_agreement"] = st.primAgreement();
    j["occlusion_agreement"] = st.occlusionAgreement();
    j["origin_ties"] = st.originTies;
    j["max_rel_dt"] = st.maxRelDt();
    j["p999_rel_dt"] = st.quantileRelDt(0.999);
    j["disagreements"] = st.firstDisagreements;
    j["bvh"] = {
        {"build_seconds", bs.buildSeconds},         {"nodes", bs.nodes},      {"leaves", bs.leaves},
        {"prims_per_leaf", bs.primitivesPerLeaf()}, {"sah_cost", bs.sahCost}, {"bytes", bs.bytes}};
    j["grid"] = {{"build_seconds", gs.buildSeconds},
                 {"cells", gs.cells},
                 {"references", gs.references},
                 {"bytes", gs.bytes}};
    for (const auto& [key, ts] :
         {std::pair{"octree", &octree.stats()}, std::pair{"kdtree", &kdtree.stats()},
          std::pair{"spheres", &spheres.stats()}})
      j[key] = {{"build_seconds", ts->buildSeconds},
                {"nodes", ts->nodes},
                {"leaves", ts->leaves},
                {"max_depth", ts->maxDepth},
                {"references", ts->references},
                {"bytes", ts->bytes}};
    j["coherence"] = {{"build_seconds", cs.buildSeconds},
                      {"origins", cs.origins},
                      {"rows", cs.rows},
                      {"objects", cs.objects},
                      {"classes", cs.classes},
                      {"references", cs.references},
                      {"bytes", cs.bytes}};
    j["embree"] = {{"build_seconds", embree.buildSeconds()}, {"bytes", embree.bytes()}};
    j["rayclass"] = {{"cells", rs.cells},
                     {"references", rs.references},
                     {"lazy_bytes", rs.lazyBytes},
                     {"cap_bytes", rs.capBytes},
                     {"fixed_bytes", rs.fixedBytes}};
    writeTextFileAtomically(a.json, j.dump(2) + "\n");
  }
  if (st.hitAgreement() < a.minAgreement || st.occlusionAgreement() < a.minAgreement) {
    std::fprintf(stderr, "glint: validation failed: agreement below %.9f\n", a.minAgreement);
    return kExitRuntime;
  }
  return kExitOk;
}

}  // namespace

CommandRunner addValidateCommand(CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Cross-check Embree against the reference BVH and the uniform grid (and brute force), hit "
      "by hit");
  cmd->add_option("scene", args->scenePath, sceneArgumentHelp())->check(CLI::ExistingFile);
  cmd->add_option("--rays", args->rays, "Random rays besides the scene's own")
      ->check(CLI::Range(0, 1 << 30));
  cmd->add_option("--seed", args->seed, "Seed of the random rays")
      ->check(wholeNumberUpTo(UINT64_MAX));
  cmd->add_option("--spp", args->spp,
                  "Camera samples per pixel for the scene's rays (0: random rays only)")
      ->check(CLI::Range(0, 1 << 16));
  cmd->add_option("--min-agreement", args->minAgreement,
                  "Fail (exit 1) when hit/miss or occlusion agreement is below this")
      ->check(CLI::Range(0.0, 1.0) & notNaN());
  cmd->add_option("--json", args->json, "Write the figures as JSON");
  takesValues(*cmd,
              cmd->add_option("--ray", args->ray,
                              "Trace one ray: nine numbers, as separate arguments or one quoted "
                              "\"ox oy oz dx dy dz tmin tmax time\" (a report line's)"),
              9, ValueKind::Number, "ox oy oz dx dy dz tmin tmax time");
  cmd->add_flag("--occluded", args->occludedRay, "With --ray: an occlusion query");
  cmd->add_flag("--no-brute", args->noBrute, "Skip the brute-force oracle");
  addAccelOptions(*cmd, args->accelOptions);
  return [args] { return runValidate(*args); };
}

}  // namespace glint
