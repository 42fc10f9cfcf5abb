#include "accel/brute_force.h"

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
    switch (g.kind) {
      case GeomKind::Mesh: {
        const TriangleMesh& m = scene_.meshes[g.index];
        for (uint32_t tri = 0; tri < m.triangleCount(); ++tri)
          record(intersectTriangle(m.vertexAt(tri, 0, r.time), m.vertexAt(tri, 1, r.time),
                                   m.vertexAt(tri, 2, r.time), r, u, v),
                 tri);
        break;
      }
      case GeomKind::Sphere:
        record(intersectSphere(scene_.sphereAt(g.index, r.time), r), 0);
        break;
      case GeomKind::Quad:
        record(intersectQuad(scene_.quads[g.index], r, u, v), 0);
        break;
      case GeomKind::Disk:
        record(intersectDisk(scene_.disks[g.index], r), 0);
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
