#include "accel/brute_force.h"

#include "accel/primitives.h"

namespace glint {

bool BruteForce::intersectGroup(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit) const {
  const auto intoInstance = [&](const Instance& inst, const Ray& r, uint32_t geom, Hit& h) {
    return intersectGroup(inst.groupId, inst.toObject(r), geom, h);
  };
  bool found = false;
  const auto& geoms = scene_.groups[groupId].geometries;
  for (uint32_t gi = 0; gi < geoms.size(); ++gi) {
    const Geometry& g = geoms[gi];
    if (g.kind == GeomKind::Plane) continue;  // shared loop in intersectPlanes
    const uint32_t prims = g.kind == GeomKind::Mesh
                               ? static_cast<uint32_t>(scene_.meshes[g.index].triangleCount())
                               : 1;
    for (uint32_t prim = 0; prim < prims; ++prim)
      found |= intersectPrimitive(scene_, groupId, gi, prim, ray, instId, hit, intoInstance);
  }
  return found;
}

Hit BruteForce::intersect(const Ray& ray) const {
  Hit hit;
  intersectGroup(0, ray, kInvalidId, hit);
  intersectPlanes(scene_, ray, hit);
  return hit;
}

bool BruteForce::occluded(const Ray& ray) const { return bool(intersect(ray)); }

}  // namespace glint
