#pragma once
// Shared by the stress suite: render a scene text in-process and read pixels back. Every
// stress scene is also rendered by the reference integrator, the production kernel's oracle,
// which must give the same image (oracle_util.h), and its hits are checked on every one of
// Glint's structures against Embree's (expectStructuresAgreeWithEmbree).
#include <cstdio>
#include <optional>
#include <set>
#include <string>

#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/ray_classification.h"
#include "accel/ray_coherence.h"
#include "accel/reference_bvh.h"
#include "accel/sphere_hierarchy.h"
#include "accel/uniform_grid.h"
#include "oracle_util.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint::stress {

// Random rays per agreement check: issue 25's 10⁶ (a twentieth under AddressSanitizer:
// test::agreementRays).
constexpr int kAgreementRays = 1000000;

// `check`'s agreement over `rays` random rays through `s` (a twentieth under AddressSanitizer):
// hit/miss and occlusion ≥ 1 − 10⁻⁶ (issue 25's bar). Hits at a ray's origin count as ties
// (CrossCheck::kOriginTolerance), but at most 10⁻⁴ of the queries may need that: a scene far
// from the origin, where every hit on a small shape lies within the tolerance, must not pass on
// ties (a sphere's box rounded inside it would make many rays disagree there).
// `minComparedHits`: the share of rays that must hit in both backends, so that the agreement
// says something about hits.
inline void expectAgreementOnRandomRays(const Scene& s, const CrossCheck& check, int rays,
                                        double minComparedHits = 0) {
  castRandomRays(s, check, test::agreementRays(rays), 21);
  const CrossCheckStats& st = check.stats();
  EXPECT_GE(double(st.relDt.size()), minComparedHits * double(st.rays));
  EXPECT_GE(st.hitAgreement(), 1 - 1e-6);
  EXPECT_GE(st.occlusionAgreement(), 1 - 1e-6);
  EXPECT_LE(double(st.originTies), 1e-4 * double(st.rays + st.occlusionRays));
  for (const auto& line : st.firstDisagreements) std::printf("disagreement: %s\n", line.c_str());
}

// As `glint validate --no-brute` checks a scene: Embree against each of Glint's own structures
// (the BVH, the grid, the octree by both walks, the k-d tree, the sphere hierarchy) on
// kAgreementRays random rays; ray classification on a tenth of them.
inline void expectStructuresAgreeWithEmbree(const Scene& s) {
  const EmbreeAccel embree(s);
  const ReferenceBvh bvh(s);
  const UniformGrid grid(s);
  const Octree octree(s);
  const Octree octreeGenerateAndTest(s, 0, Octree::Walk::GenerateAndTest);
  const KdTree kdtree(s);
  const RayCoherence coherence(s);
  const SphereHierarchy spheres(s);
  expectAgreementOnRandomRays(s,
                              CrossCheck(embree, {&bvh, &grid, &octree, &kdtree,
                                                  &octreeGenerateAndTest, &coherence, &spheres}),
                              kAgreementRays);
  // Ray classification makes its cells while tracing, and random rays, unlike a render's,
  // share few of them: each makes the cells of its own path (docs/acceleration.md), which costs
  // ten times the other structures' whole query, so it takes a tenth of the rays.
  const RayClassification rayclass(s);
  expectAgreementOnRandomRays(s, CrossCheck(embree, {&rayclass}), kAgreementRays / 10);
}

inline RenderResult renderText(const std::string& text, AccelKind kind = AccelKind::Embree,
                               std::function<void(int, int, Radiance&)> hook = nullptr) {
  const Scene s = test::sceneFromText(text);
  // Each scene text once: several cases render the same scene more than once.
  static std::set<std::string> checked;
  if (checked.insert(text).second) expectStructuresAgreeWithEmbree(s);
  const auto accel = makeAccelerator(kind, s);
  RenderOptions opt;
  opt.progress = false;
  RenderResult production = [&] {
    RenderOptions withHook = opt;
    withHook.sampleHook = hook;
    return renderScene(s, *accel, withHook);
  }();
  // A hook alters samples on their way to the film (a forced NaN): not the optics.
  if (!hook) test::expectReferenceAgrees(s, *accel, opt, production, "stress scene");
  return production;
}

inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::string vec(double x, double y, double z) {
  return "[" + num(x) + "," + num(y) + "," + num(z) + "]";
}

}  // namespace glint::stress
