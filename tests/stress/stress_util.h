#pragma once
// Shared by the stress suite: render a scene text in-process and read pixels back. Every
// stress scene is also rendered by the reference integrator, the production kernel's oracle,
// which must give the same image (oracle_util.h), and its hits are checked on every one of
// Glint's structures against Embree's (expectStructuresAgreeWithEmbree).
#include <optional>
#include <set>
#include <string>

#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/reference_bvh.h"
#include "accel/uniform_grid.h"
#include "oracle_util.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint::stress {

// Random rays per agreement check: issue 25's 10⁶; under AddressSanitizer, which makes them 10×
// slower, a tenth (enough to catch a traversal fault).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kAgreementRays = 100000;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr int kAgreementRays = 100000;
#else
constexpr int kAgreementRays = 1000000;
#endif
#else
constexpr int kAgreementRays = 1000000;
#endif

// Issue 25's bar, as `glint validate --no-brute` checks a scene: Embree and each of Glint's own
// structures (the BVH, the grid, the octree, the k-d tree) agree on hit or miss, and on
// occlusion, for all but 10⁻⁶ of kAgreementRays random rays.
inline void expectStructuresAgreeWithEmbree(const Scene& s) {
  const EmbreeAccel embree(s);
  const ReferenceBvh bvh(s);
  const UniformGrid grid(s);
  const Octree octree(s);
  const KdTree kdtree(s);
  const CrossCheck check(embree, {&bvh, &grid, &octree, &kdtree});
  castRandomRays(s, check, kAgreementRays, 21);
  EXPECT_GE(check.stats().hitAgreement(), 1 - 1e-6);
  EXPECT_GE(check.stats().occlusionAgreement(), 1 - 1e-6);
  for (const auto& line : check.stats().firstDisagreements)
    std::printf("disagreement: %s\n", line.c_str());
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
  if (!hook) test::expectReferenceAgrees(s, *accel, opt, production.film, "stress scene");
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
