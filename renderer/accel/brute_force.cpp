#include "accel/brute_force.h"

#include "accel/cutout_hits.h"
#include "scene/scene.h"

namespace glint {

void BruteForce::intersectGroup(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit) const {
  const auto& geoms = scene_.groups[groupId].geometries;
  for (uint32_t gi = 0; gi < geoms.size(); ++gi) {
    const Geometry& g = geoms[gi];
    Ray r = ray;
    r.tMax = std::min(ray.tMax, hit.t);
    float u = 0, v = 0;
    auto record = [&](float t, uint32_t prim) {
      if (t < r.tMax) {
        hit = Hit{t, u, v, gi, prim, instId};
        r.tMax = t;
      }
    };
    // The first hit of primitive `prim` that a cut-out keeps (accel/cutout_hits.h).
    const auto kept = [&](uint32_t prim, auto test) {
      return firstKeptHit(scene_, g, prim, r, u, v, test);
    };
    switch (g.kind) {
      case GeomKind::Mesh: {
        const TriangleMesh& m = scene_.meshes[g.index];
        for (uint32_t tri = 0; tri < m.triangleCount(); ++tri)
          record(kept(tri,
                      [&](const Ray& q, float& tu, float& tv) {
                        return intersectTriangle(m.vertexAt(tri, 0, q.time),
                                                 m.vertexAt(tri, 1, q.time),
                                                 m.vertexAt(tri, 2, q.time), q, tu, tv);
                      }),
                 tri);
        break;
      }
      case GeomKind::Sphere:
        record(
            kept(0, [&](const Ray& q, float&,
                        float&) { return intersectSphere(scene_.sphereAt(g.index, q.time), q); }),
            0);
        break;
      case GeomKind::Quad:
        record(kept(0, [&](const Ray& q, float& tu,
                           float& tv) { return intersectQuad(scene_.quads[g.index], q, tu, tv); }),
               0);
        break;
      case GeomKind::Disk:
        record(kept(0, [&](const Ray& q, float&,
                           float&) { return intersectDisk(scene_.disks[g.index], q); }),
               0);
        break;
      case GeomKind::Plane:
        break;  // shared loop in intersectPlanes
      case GeomKind::Instance: {
        const Instance& inst = scene_.instances[g.index];
        intersectGroup(inst.groupId, inst.toObject(r), gi, hit);
        break;
      }
    }
  }
}

Hit BruteForce::intersect(const Ray& ray) const {
  Hit hit;
  intersectGroup(0, ray, kInvalidId, hit);
  intersectPlanes(scene_, ray, hit);
  return hit;
}

bool BruteForce::occluded(const Ray& ray) const { return bool(intersect(ray)); }

}  // namespace glint
