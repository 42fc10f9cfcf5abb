#pragma once
// The reference integrator is the production kernel's oracle (DESIGN.md §3): both must render a
// scene to the same image. Bit for bit, since they trace the same rays and sum in the same
// order, except for moving geometry under Embree: Embree's packet kernels (the production
// kernel's coherent streams) and its single-ray kernels (the reference's) interpolate moving
// vertices and transforms with their operations in a different order, which moves a hit by a
// few float ulps. The normals, directions and distances shaded from it then move by a few ulps
// relative, and a pixel, a sum of products of a handful of such factors, by far less than
// 1e-5 relative (the largest difference measured is 5.96e-8 at a value near 1, one ulp, on
// scenes/animation.json). A sample that crossed a silhouette or a shadow edge would change by
// far more than 1e-5: that is not allowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/render_job.h"

namespace glint::test {

inline constexpr double kOracleMotionTolerance = 1e-5;

// Renders `scene` with the reference integrator and expects the image of `production` (rendered
// with `opt`, AOVs aside) to match it, and each pixel's rays (Radiance::rays, which adaptive
// sampling weighs) to be the same in number: a ray that one integrator leaves out of its count,
// a transparent shadow's or a light's seen alone for instance, shows here. Returns the number of
// values that differed at all.
inline int expectReferenceAgrees(const Scene& scene, const Accelerator& accel, RenderOptions opt,
                                 const RenderResult& production, const std::string& what) {
  opt.integrator = IntegratorKind::Reference;
  opt.aovs = {};
  opt.sampleHook = nullptr;
  const RenderResult reference = renderScene(scene, accel, opt);
  EXPECT_EQ(production.estimates.size(), reference.estimates.size()) << what;
  // Counts match exactly even where the values may differ by ulps (moving geometry under
  // Embree): a hit that moved to another ray tree would exceed that tolerance too.
  int miscounted = 0;
  for (size_t p = 0; p < std::min(production.estimates.size(), reference.estimates.size()); ++p)
    for (int h = 0; h < 2; ++h) {
      const uint64_t mine = production.estimates[p].half[h].rays;
      const uint64_t oracle = reference.estimates[p].half[h].rays;
      if (mine != oracle && ++miscounted <= 3)
        ADD_FAILURE() << what << ": pixel " << p << "'s half " << h << " traced " << mine
                      << " rays by the production kernel's count, " << oracle
                      << " by the reference integrator's";
    }
  const std::vector<float> a = production.film.toFloatRgba(), b = reference.film.toFloatRgba();
  EXPECT_EQ(a.size(), b.size()) << what;
  const bool exact = !scene.features.motion || accel.name() != "embree";
  int differing = 0, reported = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (a[i] == b[i]) continue;
    ++differing;
    const double tolerance = exact ? 0.0 : kOracleMotionTolerance * std::max(1.0f, std::fabs(a[i]));
    if (std::fabs(double(a[i]) - b[i]) > tolerance && ++reported <= 3)
      ADD_FAILURE() << what << ": value " << i << " (pixel " << i / 4 << ", channel " << i % 4
                    << ") is " << a[i] << " from the production kernel, " << b[i]
                    << " from the reference integrator";
  }
  return differing + miscounted;
}

}  // namespace glint::test
