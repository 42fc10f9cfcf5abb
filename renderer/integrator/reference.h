#pragma once
// Seed 002 §9.1's recursive ray tracer, written as its pseudocode is: Trace(r, d) finds the
// nearest hit, asks AccLightSource for the light the surface sends back of the ambient light,
// its own emission and each light source, and adds what its reflected and refracted child rays
// bring, recursively, depth first, one ray at a time. It calls the same material and light
// functions as the production kernel (integrator/batched_kernel.h), which traces the same tree
// in another order, and it is that kernel's oracle: both render every bundled and stress scene
// to the same image (tests/integrator/reference_test.cpp). `glint render --integrator
// reference` renders with it.
#include "accel/accelerator.h"
#include "core/sampler.h"
#include "integrator/footprint.h"
#include "integrator/medium_stack.h"
#include "integrator/radiance.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

class ReferenceIntegrator {
 public:
  // `footprintSpp`: as BatchedKernel's.
  ReferenceIntegrator(const Scene& scene, const Accelerator& accel, float minThroughput,
                      int footprintSpp)
      : scene_(scene),
        accel_(accel),
        minThroughput_(minThroughput),
        cone_(pixelCone(scene.cameraDesc, scene.render.height, footprintSpp)) {}

  // The radiance along a camera ray, sample `key`.
  Radiance radiance(const Ray& cameraRay, const SampleKey& key, RayCounters& counters) const;

 private:
  // What goes down one branch of Trace's tree with its ray.
  struct Branch {
    int depth = 0;       // d: 0 for the camera ray
    Rgb share{1, 1, 1};  // of the sample (branchShare), which the cutoff reads
    MediumStack media;   // the dielectric objects the ray is inside
    const SampleKey* key = nullptr;
    float distance = 0;  // travelled from the eye to the ray's origin (the pixel's cone)
  };

  // Trace(r, d).
  Rgb trace(const Ray& r, const Hit& hit, const Branch& branch, RayCounters& counters) const;
  // AccLightSource(q): ambient light, own emission, and each light source's share.
  Rgb accLightSource(const Material& m, const ShadingPoint& q, const SurfacePoint& at, float time,
                     const Branch& branch, RayCounters& counters) const;
  // What a shadow ray lets through: 1 or 0, or with transparent shadows the product of the
  // transmissions of the dielectrics it crosses.
  Rgb visibility(const Ray& shadow, bool atInfinity, const Branch& branch,
                 RayCounters& counters) const;

  const Scene& scene_;
  const Accelerator& accel_;
  float minThroughput_;
  PixelCone cone_;
};

}  // namespace glint
