#include "accel/primitives.h"

namespace glint {

namespace {

// Conservative bounds of a moving instance over the whole shutter. Without a change of
// rotation every point moves linearly between keys, so the union of the key boxes bounds it.
// With one, slerp can swing points outside the key boxes; every point stays within
// max|scale|·|p| of the (linearly moving) translation, which gives a safe box.
Bounds3f movingInstanceBounds(const Instance& inst, const Bounds3f& object) {
  Bounds3f out;
  if (!inst.rotates()) {
    for (const TrsKey& k : inst.motion) out.extend(transformBox(k.toTransform(), object));
    return out;
  }
  float radius = 0;
  for (int c = 0; c < 8; ++c) radius = std::max(radius, length(object.corner(c)));
  float maxScale = 0;
  for (const TrsKey& k : inst.motion) maxScale = std::max(maxScale, maxComponent(abs(k.scale)));
  const Vec3f r{radius * maxScale, radius * maxScale, radius * maxScale};
  for (const TrsKey& k : inst.motion) {
    out.extend(k.translation - r);
    out.extend(k.translation + r);
  }
  return out;
}

}  // namespace

std::vector<PrimitiveBox> groupPrimitives(const Scene& scene, uint32_t groupId,
                                          const std::function<Bounds3f(uint32_t)>& groupBox) {
  std::vector<PrimitiveBox> prims;
  const auto& geoms = scene.groups[groupId].geometries;
  for (uint32_t gi = 0; gi < geoms.size(); ++gi) {
    const Geometry& geom = geoms[gi];
    const auto add = [&](const Bounds3f& b, uint32_t prim) {
      if (!b.empty()) prims.push_back({b, gi, prim});
    };
    switch (geom.kind) {
      case GeomKind::Mesh: {
        const TriangleMesh& m = scene.meshes[geom.index];
        for (uint32_t t = 0; t < m.triangleCount(); ++t) {
          Bounds3f b;
          for (int c = 0; c < 3; ++c) {
            b.extend(m.vertex(t, c));
            for (const auto& key : m.positionKeys) b.extend(key[m.indices[3 * t + uint32_t(c)]]);
          }
          add(b, t);
        }
        break;
      }
      case GeomKind::Sphere: {
        Bounds3f b = bounds(scene.spheres[geom.index]);
        for (const Vec3f& c : scene.sphereCenterKeys[geom.index])
          b.extend(bounds(Sphere{c, scene.spheres[geom.index].radius}));
        add(b, 0);
        break;
      }
      case GeomKind::Quad:
        add(bounds(scene.quads[geom.index]), 0);
        break;
      case GeomKind::Disk:
        add(bounds(scene.disks[geom.index]), 0);
        break;
      case GeomKind::Csg:
        add(scene.csgs[geom.index].box(), 0);
        break;
      case GeomKind::Plane:
        break;  // unbounded: the shared plane loop
      case GeomKind::Instance: {
        const Instance& inst = scene.instances[geom.index];
        const Bounds3f object = groupBox(inst.groupId);
        if (object.empty()) break;
        add(inst.motion.empty() ? transformBox(inst.worldFromObject, object)
                                : movingInstanceBounds(inst, object),
            0);
        break;
      }
    }
  }
  return prims;
}

}  // namespace glint
