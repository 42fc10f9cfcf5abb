#include "app/scene_validation.h"

#include <cstdarg>
#include <cstdio>

#include "accel/cross_check.h"
#include "accel/origin_rays.h"
#include "core/error.h"
#include "core/memory.h"
#include "render/render_job.h"

namespace glint {

void checkSomethingIsCast(const ValidateSettings& settings) {
  if (settings.rays == 0 && settings.spp == 0)
    throw UsageError("--rays 0 with --spp 0 casts no ray: there would be nothing to check");
}

ValidationBackends::ValidationBackends(const Scene& scene, const ValidateSettings& settings)
    : embree(scene),
      bvh(scene),
      grid(scene),
      octree(scene),
      octreeGenerateAndTest(scene, 0, Octree::Walk::GenerateAndTest),
      kdtree(scene),
      rayclass(scene, settings.accelOptions.rayclass),
      coherence(scene),
      spheres(scene) {
  if (!settings.noBrute && scene.primitiveCount() <= kBruteForceLimit)
    brute = std::make_unique<BruteForce>(scene);
}

std::vector<const Accelerator*> ValidationBackends::others() const {
  std::vector<const Accelerator*> all{
      &bvh, &grid, &octree, &kdtree, &octreeGenerateAndTest, &rayclass, &coherence, &spheres};
  if (brute) all.push_back(brute.get());
  return all;
}

namespace {

// printf when `print`; a C variadic function, so that every call's literal format is checked
// against its values.
[[gnu::format(printf, 2, 3)]] void sayIf(bool print, const char* format, ...) {
  if (!print) return;
  va_list values;
  va_start(values, format);
  std::vprintf(format, values);
  va_end(values);
}

}  // namespace

nlohmann::json validateScene(Scene& scene, const ValidationBackends& b, const ValidateSettings& a,
                             bool print) {
  const EmbreeAccel& embree = b.embree;
  const ReferenceBvh& bvh = b.bvh;
  const UniformGrid& grid = b.grid;
  const Octree& octree = b.octree;
  const KdTree& kdtree = b.kdtree;
  const RayClassification& rayclass = b.rayclass;
  const RayCoherence& coherence = b.coherence;
  const SphereHierarchy& spheres = b.spheres;
  const std::unique_ptr<BruteForce>& brute = b.brute;
  const std::vector<const Accelerator*> others = b.others();
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
  sayIf(print,
        "backends       embree, bvh, grid, octree, kdtree, octree-generate-and-test, rayclass, "
        "coherence, spheres%s\n",
        brute ? ", brute" : " (brute force skipped: scene too large)");
  sayIf(print,
        "queries        %llu closest-hit, %llu occlusion (scene rays at %d spp + %d random + "
        "%d samples of rays from origins)\n",
        (unsigned long long)st.rays, (unsigned long long)st.occlusionRays, a.spp, a.rays,
        a.rays / 4);
  sayIf(print, "hit/miss       %.9f agreement\n", st.hitAgreement());
  sayIf(print, "primitive      %.9f agreement (ties within %.0e count as agreement)\n",
        st.primAgreement(), double(CrossCheck::kTieTolerance));
  sayIf(print, "occlusion      %.9f agreement\n", st.occlusionAgreement());
  sayIf(print, "origin ties    %llu (a hit within %.0e of the ray's origin against a miss)\n",
        (unsigned long long)st.originTies, double(CrossCheck::kOriginTolerance));
  sayIf(print, "|dt|/max(1,t)  max %.3g, 99.9th percentile %.3g\n", double(st.maxRelDt()),
        double(st.quantileRelDt(0.999)));
  sayIf(print, "embree build   %.3f s, %.1f MiB\n", embree.buildSeconds(),
        double(embree.bytes()) / (1 << 20));
  sayIf(print,
        "bvh build      %.3f s, %zu nodes, %zu leaves, %.2f prims/leaf, depth %zu, "
        "SAH cost %.2f, %.1f MiB\n",
        bs.buildSeconds, bs.nodes, bs.leaves, bs.primitivesPerLeaf(), bs.maxDepth, bs.sahCost,
        double(bs.bytes) / (1 << 20));
  const GridStats& gs = grid.stats();
  sayIf(print, "grid build     %.3f s, %zu cells, %zu references (%.2f per primitive), %.1f MiB\n",
        gs.buildSeconds, gs.cells, gs.references,
        gs.primitives ? double(gs.references) / double(gs.primitives) : 0.0,
        double(gs.bytes) / (1 << 20));
  for (const auto& [label, ts] :
       {std::pair{"octree build ", &octree.stats()}, std::pair{"kdtree build ", &kdtree.stats()},
        std::pair{"spheres build", &spheres.stats()}})
    sayIf(print,
          "%s  %.3f s, %zu nodes, %zu leaves, depth %zu, %zu references (%.2f per "
          "primitive), %.1f MiB\n",
          label, ts->buildSeconds, ts->nodes, ts->leaves, ts->maxDepth, ts->references,
          ts->referencesPerPrimitive(), double(ts->bytes) / (1 << 20));
  const RayClassStats rs = rayclass.stats();
  sayIf(print,
        "rayclass cells %zu made while tracing (n_min %u, w_min %g), %zu references (%.2f per "
        "primitive), %.1f MiB of a cap of %.1f MiB, %.1f MiB besides\n",
        rs.cells, a.accelOptions.rayclass.nMin, a.accelOptions.rayclass.wMin, rs.references,
        rs.primitives ? double(rs.references) / double(rs.primitives) : 0.0,
        double(rs.lazyBytes) / (1 << 20), double(rs.capBytes) / (1 << 20),
        double(rs.fixedBytes) / (1 << 20));
  const CoherenceStats& cs = coherence.stats();
  sayIf(print,
        "coherence build %.3f s, %zu origins (%zu with a row), %zu objects, %zu classes, %zu "
        "references, %.1f MiB\n",
        cs.buildSeconds, cs.origins, cs.rows, cs.objects, cs.classes, cs.references,
        double(cs.bytes) / (1 << 20));
  if (!st.firstDisagreements.empty()) {
    sayIf(print, "first disagreements (reproduce with glint validate SCENE --ray ...):\n");
    for (const auto& line : st.firstDisagreements) sayIf(print, "  %s\n", line.c_str());
  }
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
    j[key] = {
        {"build_seconds", ts->buildSeconds}, {"nodes", ts->nodes},           {"leaves", ts->leaves},
        {"max_depth", ts->maxDepth},         {"references", ts->references}, {"bytes", ts->bytes}};
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
  return j;
}

}  // namespace glint
