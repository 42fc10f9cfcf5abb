#include "scene/scene.h"

#include "core/check.h"

namespace glint {

const Geometry& Scene::geometry(const Hit& hit) const {
  if (hit.instId == kInvalidId) return groups[0].geometries[hit.geomId];
  const Geometry& inst = groups[0].geometries[hit.instId];
  return groups[instances[inst.index].groupId].geometries[hit.geomId];
}

ShadingPoint Scene::shadingPoint(const Ray& ray, const Hit& hit) const {
  GLINT_CHECK(bool(hit));
  const Geometry& g = geometry(hit);
  ShadingPoint sp;
  sp.t = hit.t;
  sp.materialId = g.materialId;
  sp.objectId = g.objectId;
  // Object space = world space outside instances; inside, go through the instance transform.
  const Transform* worldFromObject = nullptr;
  if (hit.instId != kInvalidId)
    worldFromObject = &instances[groups[0].geometries[hit.instId].index].worldFromObject;
  const Vec3f oObj = worldFromObject ? worldFromObject->inverse().point(ray.o) : ray.o;
  const Vec3f dObj = worldFromObject ? worldFromObject->inverse().vector(ray.d) : ray.d;

  Vec3f p, n;
  switch (g.kind) {
    case GeomKind::Mesh: {
      const TriangleMesh& m = meshes[g.index];
      const Vec3f p0 = m.vertex(hit.primId, 0), p1 = m.vertex(hit.primId, 1),
                  p2 = m.vertex(hit.primId, 2);
      p = (1 - hit.u - hit.v) * p0 + hit.u * p1 + hit.v * p2;
      n = cross(p1 - p0, p2 - p0);
      break;
    }
    case GeomKind::Sphere: {
      // Re-project onto the sphere: removes the error of o + t·d along the ray.
      const Sphere& s = spheres[g.index];
      n = oObj + hit.t * dObj - s.center;
      p = s.center + n * (s.radius / length(n));
      break;
    }
    case GeomKind::Quad: {
      const Quad& q = quads[g.index];
      p = q.corner + hit.u * q.edge1 + hit.v * q.edge2;
      n = cross(q.edge1, q.edge2);
      break;
    }
    case GeomKind::Plane: {
      const Plane& pl = planes[g.index];
      const Vec3f onRay = oObj + hit.t * dObj;
      p = onRay - dot(onRay - pl.point, pl.normal) * pl.normal;
      n = pl.normal;
      break;
    }
    case GeomKind::Instance:
      GLINT_CHECK(false);
  }
  if (worldFromObject) {
    p = worldFromObject->point(p);
    n = worldFromObject->normal(n);
  }
  sp.p = p;
  sp.ng = normalize(n);
  sp.ns = sp.ng;
  return sp;
}

Bounds3f Scene::groupBounds(uint32_t groupId) const {
  Bounds3f b;
  for (const Geometry& g : groups[groupId].geometries) {
    switch (g.kind) {
      case GeomKind::Mesh:
        b.extend(meshes[g.index].bounds());
        break;
      case GeomKind::Sphere:
        b.extend(bounds(spheres[g.index]));
        break;
      case GeomKind::Quad:
        b.extend(bounds(quads[g.index]));
        break;
      case GeomKind::Plane:
        break;
      case GeomKind::Instance: {
        const Instance& inst = instances[g.index];
        const Bounds3f ob = groupBounds(inst.groupId);
        if (ob.empty()) break;
        for (int c = 0; c < 8; ++c)
          b.extend(
              inst.worldFromObject.point({(c & 1) ? ob.hi.x : ob.lo.x, (c & 2) ? ob.hi.y : ob.lo.y,
                                          (c & 4) ? ob.hi.z : ob.lo.z}));
        break;
      }
    }
  }
  return b;
}

Bounds3f Scene::worldBounds() const { return groupBounds(0); }

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const auto& m : meshes) n += m.triangleCount();
  return n;
}

}  // namespace glint
