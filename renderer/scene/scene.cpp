#include "scene/scene.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/check.h"
#include "core/frame.h"
#include "geometry/terminator.h"

namespace glint {

namespace {

// A point on the ray projected onto the plane through `point` with unit `normal`, and its
// error bound: the projection cancels the along-normal error of o + t·d; what is left is
// rounding of the subtraction and the dot product, relative to the magnitudes involved.
// Always inlined: out of line, p and pError came back through memory.
[[gnu::always_inline]] inline void projectOntoPlane(const Vec3f& onRay, const Vec3f& point,
                                                    const Vec3f& normal, Vec3f& p, Vec3f& pError) {
  const Vec3f rel = onRay - point;
  p = onRay - dot(rel, normal) * normal;
  pError = gamma(6) * (abs(onRay) + abs(point) + abs(rel));
}

// A sphere hit re-projected onto the sphere, which removes the error of o + t·d along the ray;
// n is the outward normal (not unit).
[[gnu::always_inline]] inline void spherePoint(const Sphere& s, const Vec3f& onRay, Vec3f& p,
                                               Vec3f& pError, Vec3f& n) {
  n = onRay - s.center;
  const Vec3f q = n * (s.radius / length(n));
  p = s.center + q;
  pError = gamma(5) * abs(q) + gamma(1) * abs(p);
}

// A triangle hit from its barycentrics; n is the winding's normal (not unit).
[[gnu::always_inline]] inline void trianglePoint(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2,
                                                 float u, float v, Vec3f& p, Vec3f& pError,
                                                 Vec3f& n) {
  const float b0 = 1 - u - v;
  p = b0 * p0 + u * p1 + v * p2;
  pError = gamma(7) * (abs(b0 * p0) + abs(u * p1) + abs(v * p2));
  n = cross(p1 - p0, p2 - p0);
}

// Latitude and longitude about the y axis: u = φ/2π around it, v = 1 − θ/π from the north pole,
// so that images stand upright; tu, tv are dp/du and dp/dv.
Vec2f sphereUv(const Sphere& s, const Vec3f& p, Vec3f& tu, Vec3f& tv) {
  const Vec3f q = (p - s.center) / s.radius;
  const float phi = std::atan2(q.z, q.x), theta = std::acos(std::clamp(q.y, -1.0f, 1.0f));
  tu = 2 * kPi * s.radius * Vec3f{-q.z, 0, q.x};
  const float sinTheta = std::sqrt(std::max(0.0f, 1 - q.y * q.y));
  const float cosPhi = sinTheta > 0 ? q.x / sinTheta : 1,
              sinPhi = sinTheta > 0 ? q.z / sinTheta : 0;
  tv = -kPi * s.radius * Vec3f{q.y * cosPhi, -sinTheta, q.y * sinPhi};
  return {(phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi), 1 - theta / kPi};
}

// The world's most common hits (static flat meshes, static spheres, planes) worked out in SSE
// lanes x, y, z and a fourth nobody reads, with the Vec3f code's operations in the same order
// (so the same bits): as Vec3f, GCC split each vector into a pair and a single and spilled them.
using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));
using F2 = float __attribute__((vector_size(8)));

// One 8-byte and one 4-byte load: element by element, GCC moved x and y through a register.
[[gnu::always_inline]] inline F4 lanesOf(const Vec3f& v) {
  double xy;
  std::memcpy(&xy, &v.x, sizeof xy);
  return (F4)_mm_movelh_ps(_mm_castpd_ps(_mm_set_sd(xy)), _mm_set_ss(v.z));
}
[[gnu::always_inline]] inline F4 abs4(const F4& v) {
  return (F4)((I4)v & std::numeric_limits<int32_t>::max());
}
// dot's sum, (x + y) + z.
[[gnu::always_inline]] inline float sum3(const F4& v) { return v[0] + v[1] + v[2]; }
// storeWhole's widths (8 + 4 bytes).
[[gnu::always_inline]] inline void storeLanes(Vec3f& dst, const F4& v) {
  const F2 xy = __builtin_shufflevector(v, v, 0, 1);
  std::memcpy(&dst.x, &xy, sizeof xy);
  dst.z = v[2];
}

}  // namespace

const Geometry& Scene::geometry(const Hit& hit) const {
  if (hit.instId == kInvalidId) return groups[0].geometries[hit.geomId];
  const Geometry& inst = groups[0].geometries[hit.instId];
  return groups[instances[inst.index].groupId].geometries[hit.geomId];
}

std::vector<bool> Scene::objectIdsInWorld() const {
  std::vector<bool> shown(objectNames.size());
  const auto show = [&](uint32_t id) {
    if (id >= shown.size()) shown.resize(size_t(id) + 1);
    shown[id] = true;
  };
  const auto showMesh = [&](const Geometry& g) {
    if (g.kind != GeomKind::Mesh || meshes[g.index].objectIds.empty()) return false;
    for (uint32_t id : meshes[g.index].objectIds) show(id);
    return true;
  };
  if (groups.empty()) return shown;
  for (const Geometry& g : groups[0].geometries) {
    if (showMesh(g)) continue;
    bool named = false;  // an implicit instance of one mesh file whose triangles name objects
    if (g.kind == GeomKind::Instance)
      for (const Geometry& member : groups[instances[g.index].groupId].geometries)
        named = showMesh(member) || named;
    if (!named) show(g.objectId);
  }
  return shown;
}

Transform Instance::transformAt(float time) const {
  if (motion.empty()) return worldFromObject;
  size_t seg;
  float f;
  motionSegment(motion.size(), time, seg, f);
  return lerp(motion[seg], motion[seg + 1], f).toTransform();
}

Ray Instance::toObject(const Ray& ray) const {
  const Transform objectFromWorld = transformAt(ray.time).inverse();
  Ray local = ray;
  local.o = objectFromWorld.point(ray.o);
  local.d = objectFromWorld.vector(ray.d);
  return local;
}

Sphere Scene::sphereAt(uint32_t index, float time) const {
  const Sphere& s = spheres[index];
  if (sphereCenterKeys[index].empty()) return s;
  return {interpolateKeys(sphereCenterKeys[index], time), s.radius};
}

size_t Scene::timeSteps(const Geometry& g) const {
  switch (g.kind) {
    case GeomKind::Mesh:
      return std::max<size_t>(1, meshes[g.index].positionKeys.size());
    case GeomKind::Sphere:
      return std::max<size_t>(1, sphereCenterKeys[g.index].size());
    case GeomKind::Instance:
      return std::max<size_t>(1, instances[g.index].motion.size());
    default:
      return 1;
  }
}

bool Scene::worldPointInLanes(const Ray& ray, const Hit& hit, ShadingPoint& sp) const {
  const Geometry& g = groups[0].geometries[hit.geomId];
  F4 p, pError, n;
  switch (g.kind) {
    case GeomKind::Mesh: {  // trianglePoint
      const TriangleMesh& m = meshes[g.index];
      if (m.deforming() || m.smooth()) return false;
      const uint32_t* tri = &m.indices[3 * size_t(hit.primId)];
      const F4 p0 = lanesOf(m.positions[tri[0]]), p1 = lanesOf(m.positions[tri[1]]),
               p2 = lanesOf(m.positions[tri[2]]);
      const float b0 = 1 - hit.u - hit.v;
      const F4 a = b0 * p0, b = hit.u * p1, c = hit.v * p2;
      p = a + b + c;
      pError = gamma(7) * (abs4(a) + abs4(b) + abs4(c));
      const F4 e1 = p1 - p0, e2 = p2 - p0;
      n = __builtin_shufflevector(e1, e1, 1, 2, 0, 3) *
              __builtin_shufflevector(e2, e2, 2, 0, 1, 3) -
          __builtin_shufflevector(e1, e1, 2, 0, 1, 3) * __builtin_shufflevector(e2, e2, 1, 2, 0, 3);
      break;
    }
    case GeomKind::Sphere: {  // spherePoint
      if (!sphereCenterKeys[g.index].empty()) return false;
      const Sphere& s = spheres[g.index];
      const F4 center = lanesOf(s.center);
      n = (lanesOf(ray.o) + hit.t * lanesOf(ray.d)) - center;
      const F4 q = n * (s.radius / std::sqrt(sum3(n * n)));
      p = center + q;
      pError = gamma(5) * abs4(q) + gamma(1) * abs4(p);
      break;
    }
    case GeomKind::Plane: {  // projectOntoPlane
      const F4 onRay = lanesOf(ray.o) + hit.t * lanesOf(ray.d);
      const F4 point = lanesOf(planes[g.index].point);
      n = lanesOf(planes[g.index].normal);
      const F4 rel = onRay - point;
      p = onRay - sum3(rel * n) * n;
      pError = gamma(6) * (abs4(onRay) + abs4(point) + abs4(rel));
      break;
    }
    default:
      return false;
  }
  // A normal whose square leaves float's normal range takes shadingPoint's normalizeAnyScale.
  const float squared = sum3(n * n);
  if (!(squared >= std::numeric_limits<float>::min() &&
        squared <= std::numeric_limits<float>::max())) [[unlikely]]
    return false;
  sp.t = hit.t;
  sp.materialId = g.materialId;
  sp.objectId = g.objectId;
  storeLanes(sp.p, p);
  storeLanes(sp.pError, pError);
  const F4 ng = n * (1.0f / std::sqrt(squared));
  storeLanes(sp.ng, ng);
  storeLanes(sp.ns, ng);
  sp.lifted = false;
  if (features.surfaceCoordinates || features.vertexColors) [[unlikely]]
    addSurfaceData(g, hit, {p[0], p[1], p[2]}, ray.time, nullptr, sp);
  return true;
}

void Scene::addSurfaceData(const Geometry& g, const Hit& hit, const Vec3f& pObject, float time,
                           const Transform* worldFromObject, ShadingPoint& sp) const {
  // A CSG solid's operands carry their own materials: its hits always compute them.
  if (features.surfaceCoordinates &&
      (g.kind == GeomKind::Csg || features.readsCoordinates(g.materialId))) [[unlikely]]
    surfaceCoordinates(g, hit, pObject, time, worldFromObject, sp);
  if (features.vertexColors) [[unlikely]] {
    sp.vertexColor = Rgb{1, 1, 1};
    if (g.kind == GeomKind::Mesh && !meshes[g.index].colors.empty()) {
      const TriangleMesh& m = meshes[g.index];
      const uint32_t* tri = &m.indices[3 * size_t(hit.primId)];
      sp.vertexColor = m.colors[tri[0]] * (1 - hit.u - hit.v) + m.colors[tri[1]] * hit.u +
                       m.colors[tri[2]] * hit.v;
    }
  }
}

// Out of line, so that the hits worldPointInLanes takes do not save and restore its registers
// and stack.
template <bool kInstanced>
[[gnu::noinline]] void Scene::shadingPoint(const Ray& ray, const Hit& hit,
                                           const Transform* worldFromObject,
                                           ShadingPoint& sp) const {
  if (!kInstanced) worldFromObject = nullptr;  // so the world's copy drops the transform's code
  const Geometry& g = kInstanced ? geometry(hit) : groups[0].geometries[hit.geomId];
  sp.t = hit.t;
  sp.materialId = g.materialId;
  sp.objectId = g.objectId;
  const Vec3f oObj = worldFromObject ? worldFromObject->inverse().point(ray.o) : ray.o;
  const Vec3f dObj = worldFromObject ? worldFromObject->inverse().vector(ray.d) : ray.d;

  Vec3f p, n, pError, lift;
  const TriangleMesh* smoothMesh = nullptr;  // a mesh with vertex normals: ns is interpolated
  switch (g.kind) {
    case GeomKind::Mesh: {
      const TriangleMesh& m = meshes[g.index];
      const Vec3f p0 = m.vertexAt(hit.primId, 0, ray.time),
                  p1 = m.vertexAt(hit.primId, 1, ray.time),
                  p2 = m.vertexAt(hit.primId, 2, ray.time);
      trianglePoint(p0, p1, p2, hit.u, hit.v, p, pError, n);
      // Embree interpolates deforming vertices in its own order of operations: allow for the
      // difference to our vertexAt.
      if (m.deforming()) pError += gamma(4) * (abs(p0) + abs(p1) + abs(p2));
      if (m.smooth()) {
        smoothMesh = &m;
        // Towards the side the arriving ray came from: the lights a surface reflects are there.
        const uint32_t* tri = &m.indices[3 * size_t(hit.primId)];
        lift = smoothSurfaceLift(p, {p0, p1, p2},
                                 {m.normals[tri[0]], m.normals[tri[1]], m.normals[tri[2]]},
                                 {1 - hit.u - hit.v, hit.u, hit.v}, dot(n, dObj) < 0 ? n : -n);
      }
      break;
    }
    case GeomKind::Sphere:
      spherePoint(sphereAt(g.index, ray.time), oObj + hit.t * dObj, p, pError, n);
      break;
    case GeomKind::Csg: {
      const CsgSolid& solid = csgs[g.index];
      const CsgSurface on = solid.surface(hit.primId);
      const CsgLeaf& leaf = solid.leaves[on.leaf];
      sp.materialId = leaf.materialId;
      if (on.triangle == kInvalidId) {
        spherePoint(leaf.sphere, oObj + hit.t * dObj, p, pError, n);
      } else {
        const auto& tri = solid.triangles[on.triangle];
        trianglePoint(tri[0], tri[1], tri[2], hit.u, hit.v, p, pError, n);
      }
      if (leaf.flipped) n = -n;  // a subtracted operand bounds the solid from its inside
      break;
    }
    case GeomKind::Quad: {
      const Quad& q = quads[g.index];
      p = q.corner + hit.u * q.edge1 + hit.v * q.edge2;
      pError = gamma(4) * (abs(q.corner) + abs(hit.u * q.edge1) + abs(hit.v * q.edge2));
      n = cross(q.edge1, q.edge2);
      break;
    }
    case GeomKind::Disk:
      n = disks[g.index].normal;
      projectOntoPlane(oObj + hit.t * dObj, disks[g.index].center, n, p, pError);
      break;
    case GeomKind::Plane:
      n = planes[g.index].normal;
      projectOntoPlane(oObj + hit.t * dObj, planes[g.index].point, n, p, pError);
      break;
    case GeomKind::Instance:
      GLINT_CHECK(false);
  }
  const Vec3f pObject = p;  // for the texture coordinates below
  if (worldFromObject) {
    pError = worldFromObject->pointError(p, pError);
    p = worldFromObject->point(p);
    n = worldFromObject->normal(n);
    // A moving instance's transform is interpolated by Embree and by transformAt (ours). They
    // agree to a few ulps of the matrix, except the rotation angle: Embree's slerp takes a
    // fast acos whose absolute error (~7e-5 rad measured; tests/scene/motion_test.cpp)
    // turns the object by that much more or less, moving a point by angle × its distance from
    // the pivot. Without this a shadow ray from a turning object is blocked by the object
    // itself in Embree's version of it.
    const Instance& inst = instances[groups[0].geometries[hit.instId].index];
    if (!inst.motion.empty()) {
      pError += gamma(16) * abs(p);
      if (inst.rotates()) {
        const Vec3f pivot = worldFromObject->point({0, 0, 0});
        const float slack = kSlerpAngleError * length(p - pivot);
        pError += Vec3f{slack, slack, slack};
      }
    }
  }
  // Stored as 8 + 4 bytes (storeWhole), the widths the caller reads them back with at once:
  // store forwarding.
  storeWhole(sp.p, p);
  storeWhole(sp.pError, pError);
  const Vec3f ng = normalizeAnyScale(n);
  storeWhole(sp.ng, ng);
  storeWhole(sp.ns, smoothMesh ? smoothNormal(*smoothMesh, hit, worldFromObject, ng) : ng);
  sp.lifted = smoothMesh != nullptr;
  if (smoothMesh) storeWhole(sp.shadowLift, worldFromObject ? worldFromObject->vector(lift) : lift);
  if (features.surfaceCoordinates || features.vertexColors) [[unlikely]]
    addSurfaceData(g, hit, pObject, ray.time, worldFromObject, sp);
}

// The world's copy, for the test that compares worldPointInLanes with it.
template void Scene::shadingPoint<false>(const Ray& ray, const Hit& hit,
                                         const Transform* worldFromObject, ShadingPoint& sp) const;

void Scene::shadingPoint(const Ray& ray, const Hit& hit, ShadingPoint& sp) const {
  GLINT_CHECK(bool(hit));
  // Object space = world space outside instances; inside, go through the instance transform.
  // (A pointer, not an optional Transform, whose 128 bytes GCC cleared on every call.)
  if (hit.instId == kInvalidId) {
    sp.origin = hit.geomId;
    if (worldPointInLanes(ray, hit, sp)) [[likely]]
      return;
    return shadingPoint<false>(ray, hit, nullptr, sp);
  }
  instancePoint(ray, hit, sp);
}

void Scene::instancePoint(const Ray& ray, const Hit& hit, ShadingPoint& sp) const {
  sp.origin = hit.instId;
  const Transform worldFromObject =
      instances[groups[0].geometries[hit.instId].index].transformAt(ray.time);
  shadingPoint<true>(ray, hit, &worldFromObject, sp);
}

void Scene::surfaceCoordinates(const Geometry& g, const Hit& hit, const Vec3f& p, float time,
                               const Transform* worldFromObject, ShadingPoint& sp) const {
  Vec3f dpdu, dpdv;
  sp.uv = uvAt(g, hit, p, time, &dpdu, &dpdv);
  sp.dpdu = worldFromObject ? worldFromObject->vector(dpdu) : dpdu;
  sp.dpdv = worldFromObject ? worldFromObject->vector(dpdv) : dpdv;
  if (features.normalMaps) [[unlikely]]
    tangentFrame(g, hit, worldFromObject, sp);
  if (!features.secondUvSet) [[likely]]
    return;
  sp.uv1 = uvAt(g, hit, p, time, &dpdu, &dpdv, 1);
  sp.dpdu1 = worldFromObject ? worldFromObject->vector(dpdu) : dpdu;
  sp.dpdv1 = worldFromObject ? worldFromObject->vector(dpdv) : dpdv;
}

void Scene::tangentFrame(const Geometry& g, const Hit& hit, const Transform* worldFromObject,
                         ShadingPoint& sp) const {
  const TriangleMesh* m = g.kind == GeomKind::Mesh ? &meshes[g.index] : nullptr;
  if (!m || m->tangents.empty()) {
    // dp/du, and the side of ns × dp/du that dp/dv lies on (a mirrored mapping turns it).
    sp.tangent = sp.dpdu;
    sp.tangentSign = dot(cross(sp.ns, sp.dpdu), sp.dpdv) < 0 ? -1.0f : 1.0f;
    return;
  }
  const TriangleMesh::Tangent* corner = &m->tangents[3 * size_t(hit.primId)];
  const float b0 = 1 - hit.u - hit.v;
  const Vec3f t =
      b0 * corner[0].direction + hit.u * corner[1].direction + hit.v * corner[2].direction;
  const float sign = b0 * corner[0].sign + hit.u * corner[1].sign + hit.v * corner[2].sign;
  sp.tangent = worldFromObject ? worldFromObject->vector(t) : t;
  // A mirroring instance turns the bitangent it carries against ns × tangent.
  const bool mirrored = worldFromObject && worldFromObject->determinant() < 0;
  sp.tangentSign = (sign < 0) != mirrored ? -1.0f : 1.0f;
}

Vec2f Scene::uvAt(const Geometry& g, const Hit& hit, const Vec3f& p, float time, Vec3f* dpdu,
                  Vec3f* dpdv, int set) const {
  Vec2f uv;
  Vec3f tu, tv;  // dp/du, dp/dv
  switch (g.kind) {
    case GeomKind::Mesh: {
      const TriangleMesh& m = meshes[g.index];
      Vec2f uv0{0, 0}, uv1{1, 0}, uv2{0, 1};  // a mesh without coordinates: the barycentrics
      if (m.hasUvs()) {
        const std::vector<Vec2f>& uvs = set == 1 && !m.uvs1.empty() ? m.uvs1 : m.uvs;
        const uint32_t* tri = &m.indices[3 * size_t(hit.primId)];
        uv0 = uvs[tri[0]], uv1 = uvs[tri[1]], uv2 = uvs[tri[2]];
      }
      const float b0 = 1 - hit.u - hit.v;
      uv = {b0 * uv0.x + hit.u * uv1.x + hit.v * uv2.x, b0 * uv0.y + hit.u * uv1.y + hit.v * uv2.y};
      if (!dpdu) return uv;
      // dp/du and dp/dv from the edges and their (u, v) differences (pbrt-v4 §6.5.3).
      const Vec3f p0 = m.vertexAt(hit.primId, 0, time), p1 = m.vertexAt(hit.primId, 1, time),
                  p2 = m.vertexAt(hit.primId, 2, time);
      const float du1 = uv1.x - uv0.x, dv1 = uv1.y - uv0.y, du2 = uv2.x - uv0.x,
                  dv2 = uv2.y - uv0.y;
      const float det = du1 * dv2 - dv1 * du2;
      const Vec3f e1 = p1 - p0, e2 = p2 - p0;
      if (std::fabs(det) > 1e-20f) {
        tu = (dv2 * e1 - dv1 * e2) / det;
        tv = (du1 * e2 - du2 * e1) / det;
      }
      break;
    }
    case GeomKind::Sphere:
      uv = sphereUv(sphereAt(g.index, time), p, tu, tv);
      break;
    case GeomKind::Csg: {
      // A sphere operand as a sphere; a mesh operand's triangle by its barycentrics.
      const CsgSolid& solid = csgs[g.index];
      const CsgSurface on = solid.surface(hit.primId);
      if (on.triangle == kInvalidId) {
        uv = sphereUv(solid.leaves[on.leaf].sphere, p, tu, tv);
      } else {
        const auto& tri = solid.triangles[on.triangle];
        uv = {hit.u, hit.v};
        tu = tri[1] - tri[0];
        tv = tri[2] - tri[0];
      }
      break;
    }
    case GeomKind::Quad:
      uv = {hit.u, hit.v};
      tu = quads[g.index].edge1;
      tv = quads[g.index].edge2;
      break;
    case GeomKind::Disk:
    case GeomKind::Plane: {
      // A tangent frame of the normal, in world units from the centre (or the plane's point).
      const bool disk = g.kind == GeomKind::Disk;
      const Vec3f n = disk ? disks[g.index].normal : planes[g.index].normal;
      const Vec3f origin = disk ? disks[g.index].center : planes[g.index].point;
      orthonormalBasis(normalize(n), tu, tv);
      uv = {dot(p - origin, tu), dot(p - origin, tv)};
      break;
    }
    case GeomKind::Instance:
      break;
  }
  if (dpdu) *dpdu = tu, *dpdv = tv;
  return uv;
}

Vec2f Scene::textureCoordinates(const Geometry& g, const Ray& ray, float t, uint32_t prim, float u,
                                float v, int set) const {
  const Hit hit{t, u, v, 0, prim, kInvalidId};
  // The point shadingPoint would find; a mesh's and a quad's (u, v) come from the hit alone.
  Vec3f p, unusedError;
  if (g.kind == GeomKind::Sphere || g.kind == GeomKind::Disk || g.kind == GeomKind::Plane) {
    const Vec3f onRay = ray.o + t * ray.d;
    if (g.kind == GeomKind::Sphere) {
      const Sphere s = sphereAt(g.index, ray.time);
      const Vec3f n = onRay - s.center;
      p = s.center + n * (s.radius / length(n));
    } else if (g.kind == GeomKind::Disk) {
      projectOntoPlane(onRay, disks[g.index].center, disks[g.index].normal, p, unusedError);
    } else {
      projectOntoPlane(onRay, planes[g.index].point, planes[g.index].normal, p, unusedError);
    }
  }
  return uvAt(g, hit, p, ray.time, nullptr, nullptr, set);
}

Vec3f Scene::smoothNormal(const TriangleMesh& m, const Hit& hit, const Transform* worldFromObject,
                          const Vec3f& ng) {
  const uint32_t* tri = &m.indices[3 * size_t(hit.primId)];
  Vec3f ns = (1 - hit.u - hit.v) * m.normals[tri[0]] + hit.u * m.normals[tri[1]] +
             hit.v * m.normals[tri[2]];
  if (worldFromObject) ns = worldFromObject->normal(ns);
  const float len = length(ns);
  // Opposite vertex normals can cancel (a degenerate file): the triangle's own normal then.
  if (!(len > 1e-6f)) return ng;
  ns = ns / len;
  // On the side of ng, as ShadingPoint promises: the shading frame must not flip the surface.
  return dot(ns, ng) < 0 ? -ns : ns;
}

Bounds3f Scene::groupBounds(uint32_t groupId) const {
  Bounds3f b;
  for (const Geometry& g : groups[groupId].geometries) b.extend(geometryBounds(g));
  return b;
}

Bounds3f Scene::geometryBounds(const Geometry& g) const {
  Bounds3f b;
  switch (g.kind) {
    case GeomKind::Mesh:
      b.extend(meshes[g.index].bounds());
      break;
    case GeomKind::Sphere:
      b.extend(bounds(spheres[g.index]));
      for (const Vec3f& c : sphereCenterKeys[g.index])
        b.extend(bounds(Sphere{c, spheres[g.index].radius}));
      break;
    case GeomKind::Quad:
      b.extend(bounds(quads[g.index]));
      break;
    case GeomKind::Disk:
      b.extend(bounds(disks[g.index]));
      break;
    case GeomKind::Csg:
      b.extend(csgs[g.index].box());
      break;
    case GeomKind::Plane:
      break;
    case GeomKind::Instance: {
      // Bounds at the keys: exact for static instances; for moving ones an estimate (slerp can
      // sweep outside the key boxes), enough for what worldBounds is used for.
      const Instance& inst = instances[g.index];
      const Bounds3f ob = groupBounds(inst.groupId);
      if (ob.empty()) break;
      const size_t keys = std::max<size_t>(1, inst.motion.size());
      for (size_t k = 0; k < keys; ++k) {
        b.extend(transformBox(inst.transformAt(keys == 1 ? 0.0f : float(k) / float(keys - 1)), ob));
      }
      break;
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
