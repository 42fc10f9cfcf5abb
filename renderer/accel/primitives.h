#pragma once
// What Glint's own acceleration structures share (the reference BVH and the uniform grid): a
// group's primitives with their boxes over the whole shutter, and the hit of one primitive by
// the shared intersection routines, so that the structures differ only in how they find
// candidates.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "accel/cutout_hits.h"
#include "core/bounds.h"
#include "core/slab_test.h"
#include "scene/scene.h"

namespace glint {

// One primitive of a group: a triangle of a mesh, or a whole sphere, quad, disk, CSG solid or
// instance.
struct PrimitiveBox {
  Bounds3f box;
  uint32_t geom = 0;  // index in the group
  uint32_t prim = 0;  // triangle index, or 0
};

// What `glint validate` and the study of docs/acceleration.md report of a spatial subdivision
// (the octree and the k-d tree).
struct SubdivisionStats {
  double buildSeconds = 0;
  size_t nodes = 0, leaves = 0, references = 0, primitives = 0, maxDepth = 0, bytes = 0;
  // The octree's leaves that no surface meets (seed 002 §9.2.2), and of those the full ones
  // (inside a sphere: the solid whose inside the exact tests can tell).
  size_t emptyLeaves = 0, fullLeaves = 0;
  double referencesPerPrimitive() const {
    return primitives ? double(references) / double(primitives) : 0;
  }
};

// How many primitive references a spatial subdivision of n primitives may hold (64 per primitive
// plus 2^20) before it stops refining: n primitives that each span the whole box would
// otherwise be listed in every cell (10⁵ long triangles fanned across a scene: 10¹⁰
// references). Bundled scenes need 2–9 per primitive.
inline double referenceBudget(size_t primitives) { return 64.0 * double(primitives) + (1 << 20); }

// The bounded primitives of group `groupId` (planes, unbounded, are left to intersectPlanes),
// each boxed over every motion key; an instance's box comes from `groupBox` of the group it
// instances (empty: the instance is left out). Empty boxes are left out.
std::vector<PrimitiveBox> groupPrimitives(const Scene& scene, uint32_t groupId,
                                          const std::function<Bounds3f(uint32_t)>& groupBox);

// The hit of primitive (geom, prim) of group `groupId` closer than min(ray.tMax, hit.t), the
// first that a cut-out keeps (accel/cutout_hits.h), written to `hit`; false when there is none.
// An instance hands its object-space ray to `intoInstance(instance, ray, geom, hit)`, which
// searches the instanced group.
template <class IntoInstance>
bool intersectPrimitive(const Scene& scene, uint32_t groupId, uint32_t geom, uint32_t prim,
                        const Ray& ray, uint32_t instId, Hit& hit, IntoInstance&& intoInstance) {
  const Geometry& g = scene.groups[groupId].geometries[geom];
  Ray r = ray;
  r.tMax = std::min(ray.tMax, hit.t);
  float u = 0, v = 0, t = kInfinity;
  const auto kept = [&](auto test) { return firstKeptHit(scene, g, prim, r, u, v, test); };
  switch (g.kind) {
    case GeomKind::Mesh: {
      const TriangleMesh& m = scene.meshes[g.index];
      t = kept([&](const Ray& q, float& tu, float& tv) {
        return intersectTriangle(m.vertexAt(prim, 0, q.time), m.vertexAt(prim, 1, q.time),
                                 m.vertexAt(prim, 2, q.time), q, tu, tv);
      });
      break;
    }
    case GeomKind::Sphere:
      t = kept([&](const Ray& q, float&, float&) {
        return intersectSphere(scene.sphereAt(g.index, q.time), q);
      });
      break;
    case GeomKind::Quad:
      t = kept([&](const Ray& q, float& tu, float& tv) {
        return intersectQuad(scene.quads[g.index], q, tu, tv);
      });
      break;
    case GeomKind::Disk:
      t = kept(
          [&](const Ray& q, float&, float&) { return intersectDisk(scene.disks[g.index], q); });
      break;
    case GeomKind::Csg: {
      // The solid's first boundary: its surface id and (u, v) name the operand's surface.
      CsgBoundary b;
      if (!scene.csgs[g.index].intersect(r, b)) return false;
      hit = Hit{b.t, b.u, b.v, geom, b.surface, instId};
      return true;
    }
    case GeomKind::Plane:
      return false;
    case GeomKind::Instance:
      return intoInstance(scene.instances[g.index], r, geom, hit);
  }
  if (!(t < r.tMax)) return false;
  hit = Hit{t, u, v, geom, prim, instId};
  return true;
}

}  // namespace glint
