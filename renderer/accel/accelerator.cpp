#include "accel/accelerator.h"

#include "accel/brute_force.h"
#include "accel/cutout_hits.h"
#include "accel/embree_accel.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/ray_classification.h"
#include "accel/ray_coherence.h"
#include "accel/reference_bvh.h"
#include "accel/sphere_hierarchy.h"
#include "accel/uniform_grid.h"
#include "core/out_of_memory.h"
#include "scene/scene.h"

namespace glint {

std::string_view accelName(AccelKind k) {
  switch (k) {
    case AccelKind::Embree:
      return "embree";
    case AccelKind::Bvh:
      return "bvh";
    case AccelKind::BruteForce:
      return "brute";
    case AccelKind::Grid:
      return "grid";
    case AccelKind::Octree:
      return "octree";
    case AccelKind::KdTree:
      return "kdtree";
    case AccelKind::OctreeGenerateAndTest:
      return "octree-generate-and-test";
    case AccelKind::RayClass:
      return "rayclass";
    case AccelKind::Coherence:
      return "coherence";
    case AccelKind::Spheres:
      return "spheres";
  }
  return "?";
}

bool parseAccelKind(std::string_view name, AccelKind& out) {
  for (auto k : {AccelKind::Embree, AccelKind::Bvh, AccelKind::BruteForce, AccelKind::Grid,
                 AccelKind::Octree, AccelKind::KdTree, AccelKind::OctreeGenerateAndTest,
                 AccelKind::RayClass, AccelKind::Coherence, AccelKind::Spheres})
    if (accelName(k) == name) {
      out = k;
      return true;
    }
  return false;
}

namespace {

std::unique_ptr<Accelerator> build(AccelKind kind, const Scene& scene,
                                   const AccelOptions& options) {
  switch (kind) {
    case AccelKind::Embree:
      return std::make_unique<EmbreeAccel>(scene);
    case AccelKind::Bvh:
      return std::make_unique<ReferenceBvh>(scene);
    case AccelKind::BruteForce:
      return std::make_unique<BruteForce>(scene);
    case AccelKind::Grid:
      return std::make_unique<UniformGrid>(scene);
    case AccelKind::Octree:
      return std::make_unique<Octree>(scene);
    case AccelKind::KdTree:
      return std::make_unique<KdTree>(scene);
    case AccelKind::OctreeGenerateAndTest:
      return std::make_unique<Octree>(scene, 0, Octree::Walk::GenerateAndTest);
    case AccelKind::RayClass:
      return std::make_unique<RayClassification>(scene, options.rayclass);
    case AccelKind::Coherence:
      return std::make_unique<RayCoherence>(scene);
    case AccelKind::Spheres:
      return std::make_unique<SphereHierarchy>(scene);
  }
  return nullptr;
}

}  // namespace

std::unique_ptr<Accelerator> makeAccelerator(AccelKind kind, const Scene& scene,
                                             const AccelOptions& options) {
  return out_of_memory::whileDoing(
      "building the " + std::string(accelName(kind)) + " acceleration structure",
      [&] { return build(kind, scene, options); });
}

namespace {

// Plane i's first hit along `ray` that its material's cut-out keeps.
float keptPlaneHit(const Scene& scene, size_t i, const Ray& ray) {
  const Geometry& g = scene.groups[0].geometries[scene.planeGeometries[i]];
  float u = 0, v = 0;
  return firstKeptHit(scene, g, 0, ray, u, v, [&](const Ray& r, float&, float&) {
    return intersectPlane(scene.planes[i], r);
  });
}

// The plane loops below with `hitOf(i, ray)` for plane i's hit.
template <class HitOf>
void closestPlane(const Scene& scene, const Ray& ray, Hit& hit, HitOf hitOf) {
  for (size_t i = 0; i < scene.planes.size(); ++i) {
    Ray clipped = ray;
    clipped.tMax = std::min(ray.tMax, hit.t);
    const float t = hitOf(i, clipped);
    if (t < clipped.tMax) {
      hit = Hit{};
      hit.t = t;
      hit.geomId = scene.planeGeometries[i];
      hit.primId = 0;
    }
  }
}

template <class HitOf>
bool anyPlane(const Scene& scene, const Ray& ray, HitOf hitOf) {
  for (size_t i = 0; i < scene.planes.size(); ++i)
    if (hitOf(i, ray) < ray.tMax) return true;
  return false;
}

// Out of line, so that the plane loops every ray runs test no cut-out: a scene without cut-outs
// pays nothing for them (callgrind, docs/performance.md, "Leaving out what a scene does not need").
[[gnu::noinline]] void closestKeptPlane(const Scene& scene, const Ray& ray, Hit& hit) {
  closestPlane(scene, ray, hit, [&](size_t i, const Ray& r) { return keptPlaneHit(scene, i, r); });
}
[[gnu::noinline]] bool anyKeptPlane(const Scene& scene, const Ray& ray) {
  return anyPlane(scene, ray, [&](size_t i, const Ray& r) { return keptPlaneHit(scene, i, r); });
}

}  // namespace

void intersectPlanes(const Scene& scene, const Ray& ray, Hit& hit) {
  if (scene.features.cutouts) [[unlikely]]
    return closestKeptPlane(scene, ray, hit);
  closestPlane(scene, ray, hit,
               [&](size_t i, const Ray& r) { return intersectPlane(scene.planes[i], r); });
}

bool occludedByPlanes(const Scene& scene, const Ray& ray) {
  if (scene.features.cutouts) [[unlikely]]
    return anyKeptPlane(scene, ray);
  return anyPlane(scene, ray,
                  [&](size_t i, const Ray& r) { return intersectPlane(scene.planes[i], r); });
}

}  // namespace glint
