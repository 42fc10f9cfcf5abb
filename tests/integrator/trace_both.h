#pragma once
// One ray through a small scene, traced by the production kernel and by its oracle, the
// reference integrator: every closed-form test of the optics checks both, and that they agree
// bit for bit (one ray, one sample: there is no summation order to differ in).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "integrator/batched_kernel.h"
#include "integrator/reference.h"
#include "test_util.h"

namespace glint::test {

struct Traced {
  Scene scene;
  std::unique_ptr<Accelerator> accel;

  Rgb trace(const Ray& ray, float minThroughput = kDefaultMinThroughput, int px = 0,
            uint64_t seed = 0) const {
    const Sampler sampler(SamplerKind::Stratified, 1, seed);
    const SampleKey key(&sampler, px, 0, 0);
    RayCounters productionCounters, referenceCounters;
    const Radiance production = BatchedKernel(scene, *accel, minThroughput, scene.render.spp)
                                    .trace(ray, key, productionCounters);
    const Radiance reference = ReferenceIntegrator(scene, *accel, minThroughput, scene.render.spp)
                                   .radiance(ray, key, referenceCounters);
    EXPECT_EQ(production.L, reference.L) << "the production kernel and its oracle disagree";
    // They trace the same rays, and each says so for the sample (Radiance::rays, the cost
    // adaptive sampling weighs).
    EXPECT_EQ(production.rays, reference.rays);
    EXPECT_EQ(production.rays, productionCounters.total());
    EXPECT_EQ(reference.rays, referenceCounters.total());
    return production.L;
  }
};

// The eye sits at the world origin, so render space (world − eye, io/placement.h) is world
// space and rays can be written in world coordinates. `body` holds the scene's other keys.
inline Traced load(const std::string& body) {
  Traced t{sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]}, )" + body + "}"),
           nullptr};
  t.accel = makeAccelerator(AccelKind::Embree, t.scene);
  return t;
}

inline Ray rayTo(Vec3f from, Vec3f to) { return {from, normalize(to - from)}; }

// spawnRay moves an origin off the surface by its error bound: for a face at coordinate c
// (all vertices at c) that is γ₇·|c| ≈ 3.5 ulps of c, plus one ulp of rounding. A path through
// an absorbing medium is shortened by that at each entry, and Beer's factor a^s errs by about
// |ln a|·(shortening) relative. Tolerances use 16 ulps of c, above that bound.
inline double spawnOffset(float coordinate) {
  return 16.0 * (std::nextafter(coordinate, kInfinity) - coordinate);
}

}  // namespace glint::test
