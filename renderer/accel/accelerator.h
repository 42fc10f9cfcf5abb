#pragma once
// The intersection seam (DESIGN.md §3): backends answer only with Hit. Planes are unbounded and
// fit no hierarchy, so every backend tests them with the same shared loop (intersectPlanes).
#include <cstddef>
#include <memory>
#include <string_view>

#include "accel/ray_classification_settings.h"
#include "core/ray.h"
#include "geometry/hit.h"

namespace glint {

class Scene;

enum class AccelKind {
  Embree,
  Bvh,
  BruteForce,
  Grid,
  Octree,
  KdTree,
  OctreeGenerateAndTest,
  RayClass,
  Coherence,
  Spheres
};

std::string_view accelName(AccelKind);
bool parseAccelKind(std::string_view name, AccelKind& out);

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  virtual Hit intersect(const Ray&) const = 0;  // closest hit in (tMin, tMax) at ray.time
  virtual bool occluded(const Ray&) const = 0;  // any hit in (tMin, tMax)
  // Closest hits of n rays that start close together and point alike (camera rays of one
  // pixel); a backend may trace them as packets. The hits are those intersect() would give,
  // up to the rounding of the packet kernels.
  virtual void intersectCoherent(const Ray* rays, Hit* hits, size_t n) const {
    for (size_t i = 0; i < n; ++i) hits[i] = intersect(rays[i]);
  }
  // Whether each of n rays is blocked, as occluded() would answer, for rays that start close
  // together and point alike (the shadow rays of neighbouring shading points towards one
  // light); a backend may trace them as packets.
  virtual void occludedCoherent(const Ray* rays, bool* blocked, size_t n) const {
    for (size_t i = 0; i < n; ++i) blocked[i] = occluded(rays[i]);
  }
  virtual std::string_view name() const = 0;
};

// What the command line may set of the backends that have settings (app/accel_options.h).
struct AccelOptions {
  RayClassSettings rayclass;
};

std::unique_ptr<Accelerator> makeAccelerator(AccelKind, const Scene&, const AccelOptions& = {});

// Closest plane hit of the world group closer than hit.t; updates `hit` in place.
void intersectPlanes(const Scene& scene, const Ray& ray, Hit& hit);
bool occludedByPlanes(const Scene& scene, const Ray& ray);
// The same for n rays at once, each ray's answer that of the one-ray form: a backend that traces
// rays in streams tests each plane against the whole stream.
void intersectPlanes(const Scene& scene, const Ray* rays, Hit* hits, size_t n);
void occludedByPlanes(const Scene& scene, const Ray* rays, bool* blocked, size_t n);

}  // namespace glint
