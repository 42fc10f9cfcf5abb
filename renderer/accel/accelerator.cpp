#include "accel/accelerator.h"

#include <cstddef>
#include <cstring>

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

namespace {

using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));

static_assert(offsetof(Ray, o) == 0 && offsetof(Ray, d) == 12 && offsetof(Ray, tMin) == 24 &&
              offsetof(Ray, tMax) == 28 && sizeof(Vec3f) == 12);

// Four rays side by side: ray j's fields in lane j.
struct FourRays {
  F4 ox, oy, oz, dx, dy, dz, tMin, tMax;
};

[[gnu::always_inline]] inline F4 load4(const float* p) {
  F4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Rows to columns: lane j of row i becomes lane i of row j.
[[gnu::always_inline]] inline void transpose(F4& a, F4& b, F4& c, F4& d) {
  const F4 ab0 = __builtin_shufflevector(a, b, 0, 4, 1, 5);
  const F4 ab1 = __builtin_shufflevector(a, b, 2, 6, 3, 7);
  const F4 cd0 = __builtin_shufflevector(c, d, 0, 4, 1, 5);
  const F4 cd1 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
  a = __builtin_shufflevector(ab0, cd0, 0, 1, 4, 5);
  b = __builtin_shufflevector(ab0, cd0, 2, 3, 6, 7);
  c = __builtin_shufflevector(ab1, cd1, 0, 1, 4, 5);
  d = __builtin_shufflevector(ab1, cd1, 2, 3, 6, 7);
}

[[gnu::always_inline]] inline FourRays loadFourRays(const Ray* r) {
  // (o.x, o.y, o.z, d.x) and (d.y, d.z, tMin, tMax) of each ray, turned into lanes.
  F4 a0 = load4(&r[0].o.x), a1 = load4(&r[1].o.x), a2 = load4(&r[2].o.x), a3 = load4(&r[3].o.x);
  F4 b0 = load4(&r[0].d.y), b1 = load4(&r[1].d.y), b2 = load4(&r[2].d.y), b3 = load4(&r[3].d.y);
  transpose(a0, a1, a2, a3);
  transpose(b0, b1, b2, b3);
  return {a0, a1, a2, a3, b0, b1, b2, b3};
}

// intersectPlane for four rays ending at `tMax`, its operations in its order (so the same
// bits): the lanes whose ray meets the plane in (tMin, tMax), and there at `t`.
[[gnu::always_inline]] inline I4 planeLanes(const Plane& p, const FourRays& r, F4 tMax, F4& t) {
  const F4 denom = p.normal.x * r.dx + p.normal.y * r.dy + p.normal.z * r.dz;
  t = ((p.point.x - r.ox) * p.normal.x + (p.point.y - r.oy) * p.normal.y +
       (p.point.z - r.oz) * p.normal.z) /
      denom;
  return (denom != 0) & (t > r.tMin) & (t < tMax);
}

}  // namespace

void intersectPlanes(const Scene& scene, const Ray* rays, Hit* hits, size_t n) {
  if (scene.features.cutouts) [[unlikely]] {
    for (size_t k = 0; k < n; ++k) closestKeptPlane(scene, rays[k], hits[k]);
    return;
  }
  // Plane by plane over the stream, four rays a step: each ray still meets the planes in the
  // one-ray order, and a plane costs a few vector operations a ray instead of a call.
  for (size_t i = 0; i < scene.planes.size(); ++i) {
    const Plane plane = scene.planes[i];
    const uint32_t geomId = scene.planeGeometries[i];
    auto take = [&](size_t k, float t) {
      hits[k] = Hit{};
      hits[k].t = t;
      hits[k].geomId = geomId;
      hits[k].primId = 0;
    };
    size_t k = 0;
    for (; k + 4 <= n; k += 4) {
      const FourRays r = loadFourRays(rays + k);
      const F4 hitT = {hits[k].t, hits[k + 1].t, hits[k + 2].t, hits[k + 3].t};
      // std::min(ray.tMax, hit.t), as the one-ray loop clips.
      const I4 nearer = hitT < r.tMax;
      const F4 clip = (F4)((nearer & (I4)hitT) | (~nearer & (I4)r.tMax));
      F4 t;
      const I4 met = planeLanes(plane, r, clip, t);
      for (int j = 0; j < 4; ++j)
        if (met[j]) take(k + j, t[j]);
    }
    for (; k < n; ++k) {
      Ray clipped = rays[k];
      clipped.tMax = std::min(rays[k].tMax, hits[k].t);
      const float t = intersectPlane(plane, clipped);
      if (t < clipped.tMax) take(k, t);
    }
  }
}

void occludedByPlanes(const Scene& scene, const Ray* rays, bool* blocked, size_t n) {
  if (scene.features.cutouts) [[unlikely]] {
    for (size_t k = 0; k < n; ++k) blocked[k] = anyKeptPlane(scene, rays[k]);
    return;
  }
  size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    const FourRays r = loadFourRays(rays + k);
    I4 met = {0, 0, 0, 0};
    for (const Plane& p : scene.planes) {
      F4 t;
      met |= planeLanes(p, r, r.tMax, t);
    }
    for (int j = 0; j < 4; ++j) blocked[k + j] = met[j] != 0;
  }
  for (; k < n; ++k) {
    blocked[k] = false;
    for (const Plane& p : scene.planes) blocked[k] |= intersectPlane(p, rays[k]) < rays[k].tMax;
  }
}

}  // namespace glint
