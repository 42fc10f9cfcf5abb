#include "accel/embree_accel.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>

#include "accel/cutout_hits.h"
#include "core/error.h"
#include "core/motion.h"
#include "core/seconds_since.h"
#include "geometry/shape_lanes.h"
#include "scene/scene.h"

#include <embree3/rtcore_quaternion.h>

namespace glint {

static_assert(kMaxMotionKeys == RTC_MAX_TIME_STEP_COUNT, "the loader's limit is Embree's");

namespace {

thread_local std::string tEmbreeError;

void onEmbreeError(void*, RTCError code, const char* str) {
  tEmbreeError = std::string("Embree error ") + std::to_string(int(code)) + ": " +
                 (str ? str : "(no message)");
}

std::atomic<int64_t> gEmbreeBytes{0};

bool onEmbreeMemory(void*, ssize_t bytes, bool) {
  gEmbreeBytes += bytes;
  return true;  // never refuse: out-of-memory surfaces as std::bad_alloc
}

struct DeviceHolder {
  RTCDevice device = nullptr;
  DeviceHolder() {
    device = rtcNewDevice(nullptr);
    if (!device) {
      const RTCError code = rtcGetDeviceError(nullptr);
      // Embree starts its threads here; without address space for their stacks it fails.
      if (code == RTC_ERROR_OUT_OF_MEMORY || code == RTC_ERROR_UNKNOWN)
        throw OutOfMemoryError("out of memory: cannot create the Embree device (Embree error " +
                               std::to_string(int(code)) + ")");
      throw GlintError("cannot create the Embree device (rtcNewDevice failed, Embree error " +
                       std::to_string(int(code)) + ")");
    }
    rtcSetDeviceErrorFunction(device, onEmbreeError, nullptr);
    rtcSetDeviceMemoryMonitorFunction(device, onEmbreeMemory, nullptr);
  }
  ~DeviceHolder() { rtcReleaseDevice(device); }
};

}  // namespace

int64_t embreeMemoryBytes() { return gEmbreeBytes.load(); }

RTCDevice embreeDevice() {
  static DeviceHolder holder;
  return holder.device;
}

void throwIfEmbreeFailed(const char* what) {
  const RTCError code = rtcGetDeviceError(embreeDevice());
  if (code == RTC_ERROR_NONE && tEmbreeError.empty()) return;
  std::string msg =
      tEmbreeError.empty() ? "Embree error " + std::to_string(int(code)) : tEmbreeError;
  tEmbreeError.clear();
  if (code == RTC_ERROR_OUT_OF_MEMORY) throw OutOfMemoryError(std::string(what) + ": " + msg);
  throw GlintError(std::string(what) + ": " + msg);
}

std::string embreeVersionString() {
  const auto v = rtcGetDeviceProperty(embreeDevice(), RTC_DEVICE_PROPERTY_VERSION);
  return std::to_string(v / 10000) + "." + std::to_string((v / 100) % 100) + "." +
         std::to_string(v % 100);
}

struct EmbreeAccel::UserShape {
  GeomKind kind;
  const Scene* scene = nullptr;
  uint32_t index = 0;  // into scene->spheres, quads, disks, csgs or meshes
  bool lanes = false;  // a quad or a sphere that does not move: packets test it lane-parallel
                       // (disks, which only visible lights make, are tested one ray at a time)
  const Geometry* cutout = nullptr;  // the entry, when its material has a cut-out
};

namespace {

Ray toRay(RTCRayN* rays, unsigned N, unsigned i) {
  Ray r;
  r.o = {RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i)};
  r.d = {RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i)};
  r.tMin = RTCRayN_tnear(rays, N, i);
  r.tMax = RTCRayN_tfar(rays, N, i);
  r.time = RTCRayN_time(rays, N, i);
  return r;
}

float intersectShape(const EmbreeAccel::UserShape& s, const Ray& r, float& u, float& v) {
  if (s.kind == GeomKind::Sphere) return intersectSphere(s.scene->sphereAt(s.index, r.time), r);
  if (s.kind == GeomKind::Disk) return intersectDisk(s.scene->disks[s.index], r);
  return intersectQuad(s.scene->quads[s.index], r, u, v);
}

// The shape's first hit that its cut-out keeps (accel/cutout_hits.h). Out of line: inlined
// beside intersectShape it keeps GCC from inlining the shape tests.
[[gnu::noinline]] float keptUserHit(const EmbreeAccel::UserShape& s, const Ray& r, float& u,
                                    float& v) {
  return firstKeptHit(*s.scene, *s.cutout, 0, r, u, v, [&](const Ray& q, float& tu, float& tv) {
    return intersectShape(s, q, tu, tv);
  });
}

float intersectUser(const EmbreeAccel::UserShape& s, const Ray& r, float& u, float& v) {
  if (s.cutout) [[unlikely]]
    return keptUserHit(s, r, u, v);
  return intersectShape(s, r, u, v);
}

// Triangles of a mesh with a cut-out: Embree offers each candidate hit, at the ray's tfar (for
// closest hits and for occlusion), and those in a hole are refused.
void cutoutFilter(const RTCFilterFunctionNArguments* args) {
  const auto& s = *static_cast<const EmbreeAccel::UserShape*>(args->geometryUserPtr);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] == 0) continue;
    if (s.scene->cutAway(*s.cutout, toRay(args->ray, N, i), RTCRayN_tfar(args->ray, N, i),
                         RTCHitN_primID(args->hit, N, i), RTCHitN_u(args->hit, N, i),
                         RTCHitN_v(args->hit, N, i)))
      args->valid[i] = 0;
  }
}

void userBounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = *static_cast<const EmbreeAccel::UserShape*>(args->geometryUserPtr);
  Bounds3f b;
  if (s.kind == GeomKind::Sphere) {
    // Moving spheres: Embree asks for the bounds at each time step and interpolates them
    // linearly, which contains a sphere whose centre moves linearly between the keys.
    const auto& keys = s.scene->sphereCenterKeys[s.index];
    const Sphere& sphere = s.scene->spheres[s.index];
    b = bounds(keys.empty() ? sphere : Sphere{keys[args->timeStep], sphere.radius});
  } else if (s.kind == GeomKind::Disk) {
    b = bounds(s.scene->disks[s.index]);
  } else if (s.kind == GeomKind::Csg) {
    b = s.scene->csgs[s.index].box();
  } else {
    b = bounds(s.scene->quads[s.index]);
  }
  *args->bounds_o = {b.lo.x, b.lo.y, b.lo.z, 0, b.hi.x, b.hi.y, b.hi.z, 0};
}

// Lanes of a packet (coherent streams: 16 rays at a time where Embree runs AVX-512) that meet
// a static sphere or a quad: tested side by side, the same bits as one at a time.
uint32_t hitLanes(const EmbreeAccel::UserShape& s, const RTCIntersectFunctionNArguments* args,
                  RTCRayN* rays, LaneHits& hits) {
  const unsigned N = args->N;
  const RayLanes lanes{
      {&RTCRayN_org_x(rays, N, 0), &RTCRayN_org_y(rays, N, 0), &RTCRayN_org_z(rays, N, 0)},
      {&RTCRayN_dir_x(rays, N, 0), &RTCRayN_dir_y(rays, N, 0), &RTCRayN_dir_z(rays, N, 0)},
      &RTCRayN_tnear(rays, N, 0),
      &RTCRayN_tfar(rays, N, 0),
      args->valid};
  const int n = static_cast<int>(N);
  return s.kind == GeomKind::Sphere ? intersectLanes(s.scene->spheres[s.index], lanes, n, hits)
                                    : intersectLanes(s.scene->quads[s.index], lanes, n, hits);
}

// Lane i of the packet hits at t, (u, v).
[[gnu::always_inline]] inline void recordHit(const RTCIntersectFunctionNArguments* args,
                                             RTCRayN* rays, RTCHitN* hits, unsigned i, float t,
                                             float u, float v) {
  const unsigned N = args->N;
  RTCRayN_tfar(rays, N, i) = t;
  RTCHitN_u(hits, N, i) = u;
  RTCHitN_v(hits, N, i) = v;
  RTCHitN_Ng_x(hits, N, i) = 0;  // Glint rebuilds normals itself (Scene::shadingPoint)
  RTCHitN_Ng_y(hits, N, i) = 0;
  RTCHitN_Ng_z(hits, N, i) = 1;
  RTCHitN_primID(hits, N, i) = args->primID;
  RTCHitN_geomID(hits, N, i) = args->geomID;
  RTCHitN_instID(hits, N, i, 0) = args->context->instID[0];
}

void userIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& s = *static_cast<const EmbreeAccel::UserShape*>(args->geometryUserPtr);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  if (s.lanes && args->N > 1 && args->N <= unsigned(kMaxLanes)) {
    LaneHits found;
    for (uint32_t lanes = hitLanes(s, args, rays, found); lanes != 0; lanes &= lanes - 1) {
      const auto i = static_cast<unsigned>(std::countr_zero(lanes));
      recordHit(args, rays, hits, i, found.t[i], found.u[i], found.v[i]);
    }
    return;
  }
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const Ray r = toRay(rays, args->N, i);
    float u = 0, v = 0;
    const float t = intersectUser(s, r, u, v);
    if (t < r.tMax) recordHit(args, rays, hits, i, t, u, v);
  }
}

void userOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto& s = *static_cast<const EmbreeAccel::UserShape*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const Ray r = toRay(args->ray, args->N, i);
    float u = 0, v = 0;
    if (intersectUser(s, r, u, v) < r.tMax) RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
  }
}

// A CSG solid: its first boundary, on the surface (primitive id) of the operand it lies on.
void csgIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& s = *static_cast<const EmbreeAccel::UserShape*>(args->geometryUserPtr);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    CsgBoundary b;
    if (!args->valid[i] || !s.scene->csgs[s.index].intersect(toRay(rays, args->N, i), b)) continue;
    recordHit(args, rays, hits, i, b.t, b.u, b.v);
    RTCHitN_primID(hits, args->N, i) = b.surface;
  }
}

void csgOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto& s = *static_cast<const EmbreeAccel::UserShape*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    CsgBoundary b;
    if (args->valid[i] && s.scene->csgs[s.index].intersect(toRay(args->ray, args->N, i), b))
      RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
  }
}

}  // namespace

namespace {

// How much an instance's inverse grows coordinates: |inverse · x|∞ ≤ growth · |x|∞ + shift.
struct Growth {
  float growth = 1, shift = 0;
};

Growth growthOf(const Instance& inst) {
  Growth out;
  if (inst.motion.empty()) {
    const Mat4& inv = inst.worldFromObject.inverseMatrix();
    for (int r = 0; r < 3; ++r) {
      out.growth =
          std::max(out.growth, std::fabs(inv(r, 0)) + std::fabs(inv(r, 1)) + std::fabs(inv(r, 2)));
      out.shift = std::max(out.shift, std::fabs(inv(r, 3)));
    }
    return out;
  }
  // S⁻¹ R⁻¹ (x − t) at each key: a rotation grows a coordinate by at most √3; scale is
  // interpolated between keys, so its smallest magnitude at a key bounds it.
  for (const TrsKey& k : inst.motion) {
    const float s = std::min({std::fabs(k.scale.x), std::fabs(k.scale.y), std::fabs(k.scale.z)});
    const float g = std::sqrt(3.0f) / s;
    const float t = std::max(
        {std::fabs(k.translation.x), std::fabs(k.translation.y), std::fabs(k.translation.z)});
    out.growth = std::max(out.growth, g);
    out.shift = std::max(out.shift, g * t);
  }
  return out;
}

// The object whose instance grows coordinates most, for the refusal to name: a world entry's
// name, or "an instance inside a group" when the worst one is nested.
std::string mostShrinkingObject(const Scene& scene) {
  float worst = -1;
  for (const Instance& inst : scene.instances) worst = std::max(worst, growthOf(inst).growth);
  for (const Geometry& g : scene.groups[0].geometries)
    if (g.kind == GeomKind::Instance && growthOf(scene.instances[g.index]).growth == worst)
      return scene.objectName(g.objectId);
  return "an instance inside a group";
}

}  // namespace

EmbreeAccel::RayRange embreeRayRange(const Scene& scene) {
  // Rounding in Embree's own transform of the ray: a few ulps, far inside 1 %.
  const float limit = 0.99f * kEmbreeMaxRayCoordinate;
  float growth = 1, shift = 0;
  for (const Instance& inst : scene.instances) {
    const Growth g = growthOf(inst);
    growth = std::max(growth, g.growth);
    shift = std::max(shift, g.shift);
  }
  EmbreeAccel::RayRange range;
  range.direction = std::isfinite(growth) ? limit / growth : 0;
  range.origin = std::isfinite(growth) && shift < limit ? (limit - shift) / growth : 0;
  return range;
}

EmbreeAccel::EmbreeAccel(const Scene& scene) : scene_(scene), range_(embreeRayRange(scene)) {
  // Rays start on the scene's surfaces (and at the camera, the origin of render space), which
  // the loader keeps within kMaxRayOrigin: where instances shrink the range below that, an
  // instance whose inverse grows coordinates so much that Embree could not take rays from the
  // scene's surfaces would have them dropped, so the scene is refused instead.
  if (range_.origin < kMaxRayOrigin) {
    std::vector<std::optional<Bounds3f>> groupBox(scene.groups.size());
    Bounds3f box;
    for (const Geometry& g : scene.groups[0].geometries) {
      if (g.kind != GeomKind::Instance) {
        box.extend(scene.geometryBounds(g));
        continue;
      }
      const Instance& inst = scene.instances[g.index];
      std::optional<Bounds3f>& ob = groupBox[inst.groupId];
      if (!ob) ob = scene.groupBounds(inst.groupId);
      if (ob->empty()) continue;
      const size_t keys = std::max<size_t>(1, inst.motion.size());
      for (size_t k = 0; k < keys; ++k)
        box.extend(
            transformBox(inst.transformAt(keys == 1 ? 0.0f : float(k) / float(keys - 1)), *ob));
    }
    const float extent =
        box.empty() ? 0.0f
                    : std::max({std::fabs(box.lo.x), std::fabs(box.lo.y), std::fabs(box.lo.z),
                                std::fabs(box.hi.x), std::fabs(box.hi.y), std::fabs(box.hi.z)});
    if (!(extent <= range_.origin)) {
      char text[700];  // the name has at most 256 characters
      std::snprintf(text, sizeof text,
                    "the scene reaches %g from the camera, but the transform of %s shrinks so "
                    "much that Embree takes rays only from within %g (in its space they would "
                    "pass Embree's 1.844e18): scale it less or bring the scene closer",
                    double(extent), mostShrinkingObject(scene).c_str(), double(range_.origin));
      throw UsageError(text);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const int64_t bytesBefore = embreeMemoryBytes();
  groupScenes_.assign(scene.groups.size(), nullptr);
  try {
    // Instanced groups first: the world's instances refer to their committed scenes.
    for (uint32_t g = 1; g < scene.groups.size(); ++g) groupScenes_[g] = buildGroup(g);
    groupScenes_[0] = buildGroup(0);
  } catch (...) {
    // The destructor does not run for a constructor that throws: release what was built.
    for (RTCScene built : groupScenes_)
      if (built) rtcReleaseScene(built);
    throw;
  }
  buildSeconds_ = secondsSince(start);
  bytes_ = embreeMemoryBytes() - bytesBefore;
}

EmbreeAccel::~EmbreeAccel() {
  for (RTCScene s : groupScenes_)
    if (s) rtcReleaseScene(s);
}

RTCScene EmbreeAccel::buildGroup(uint32_t groupId) {
  RTCDevice device = embreeDevice();
  RTCScene rtcScene = rtcNewScene(device);
  try {
    addGeometries(rtcScene, groupId);
  } catch (...) {
    rtcReleaseScene(rtcScene);
    throw;
  }
  return rtcScene;
}

void EmbreeAccel::addGeometries(RTCScene rtcScene, uint32_t groupId) {
  RTCDevice device = embreeDevice();
  const auto& geoms = scene_.groups[groupId].geometries;
  for (uint32_t gi = 0; gi < geoms.size(); ++gi) {
    const Geometry& g = geoms[gi];
    RTCGeometry geom = nullptr;
    switch (g.kind) {
      case GeomKind::Mesh: {
        const TriangleMesh& m = scene_.meshes[g.index];
        geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (m.deforming()) {
          // One vertex buffer per key; Embree interpolates linearly at ray.time.
          rtcSetGeometryTimeStepCount(geom, static_cast<unsigned>(m.positionKeys.size()));
          for (unsigned k = 0; k < m.positionKeys.size(); ++k)
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, k, RTC_FORMAT_FLOAT3,
                                       m.positionKeys[k].data(), 0, sizeof(Vec3f),
                                       m.positionKeys[k].size());
        } else {
          rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                     m.positions.data(), 0, sizeof(Vec3f), m.positions.size());
        }
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                   m.indices.data(), 0, 3 * sizeof(uint32_t), m.triangleCount());
        if (scene_.hasCutout(g)) {
          auto shape = std::make_unique<UserShape>(UserShape{g.kind, &scene_, g.index, false, &g});
          rtcSetGeometryUserData(geom, shape.get());
          rtcSetGeometryIntersectFilterFunction(geom, cutoutFilter);
          rtcSetGeometryOccludedFilterFunction(geom, cutoutFilter);
          userShapes_.push_back(std::move(shape));
        }
        break;
      }
      case GeomKind::Sphere:
      case GeomKind::Quad:
      case GeomKind::Disk: {
        const bool cutout = scene_.hasCutout(g);
        // A cut-out is tested one ray at a time, beside its hole test.
        const bool lanes =
            !cutout && ((g.kind == GeomKind::Quad && quadNormalInRange(scene_.quads[g.index])) ||
                        (g.kind == GeomKind::Sphere && scene_.sphereCenterKeys[g.index].empty()));
        auto shape = std::make_unique<UserShape>(
            UserShape{g.kind, &scene_, g.index, lanes, cutout ? &g : nullptr});
        geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        // Time steps only for what moves: a static scene gets none.
        if (const size_t steps = scene_.timeSteps(g); steps > 1)
          rtcSetGeometryTimeStepCount(geom, static_cast<unsigned>(steps));
        rtcSetGeometryUserPrimitiveCount(geom, 1);
        rtcSetGeometryUserData(geom, shape.get());
        rtcSetGeometryBoundsFunction(geom, userBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, userIntersect);
        rtcSetGeometryOccludedFunction(geom, userOccluded);
        userShapes_.push_back(std::move(shape));
        break;
      }
      case GeomKind::Csg: {
        auto shape = std::make_unique<UserShape>(UserShape{g.kind, &scene_, g.index});
        geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, 1);
        rtcSetGeometryUserData(geom, shape.get());
        rtcSetGeometryBoundsFunction(geom, userBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, csgIntersect);
        rtcSetGeometryOccludedFunction(geom, csgOccluded);
        userShapes_.push_back(std::move(shape));
        break;
      }
      case GeomKind::Plane:
        continue;  // unbounded: the shared plane loop handles it
      case GeomKind::Instance: {
        const Instance& inst = scene_.instances[g.index];
        geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, groupScenes_[inst.groupId]);
        if (inst.motion.empty()) {
          rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR,
                                  inst.worldFromObject.matrix().m.data());
          break;
        }
        // Quaternion motion: Embree interpolates scale and translation linearly and the
        // rotation by slerp, the same as Instance::transformAt.
        rtcSetGeometryTimeStepCount(geom, static_cast<unsigned>(inst.motion.size()));
        for (unsigned k = 0; k < inst.motion.size(); ++k) {
          const TrsKey& key = inst.motion[k];
          RTCQuaternionDecomposition qd;
          rtcInitQuaternionDecomposition(&qd);
          rtcQuaternionDecompositionSetScale(&qd, key.scale.x, key.scale.y, key.scale.z);
          rtcQuaternionDecompositionSetQuaternion(&qd, key.rotation.w, key.rotation.x,
                                                  key.rotation.y, key.rotation.z);
          rtcQuaternionDecompositionSetTranslation(&qd, key.translation.x, key.translation.y,
                                                   key.translation.z);
          rtcSetGeometryTransformQuaternion(geom, k, &qd);
        }
        break;
      }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(rtcScene, geom, gi);
    rtcReleaseGeometry(geom);
    throwIfEmbreeFailed("building the Embree scene");
  }
  rtcCommitScene(rtcScene);
  throwIfEmbreeFailed("committing the Embree scene");
}

namespace {

// Every ray Embree is given passes here: one outside `range` becomes an empty segment
// (tnear 1 > tfar 0), which Embree accepts and which hits nothing and blocks nothing.
// Inline: a call per ray costs the streams more than the copy itself.
[[gnu::always_inline]] inline RTCRay toRtcRay(const Ray& ray, const EmbreeAccel::RayRange& range) {
  if (!range.takes(ray)) return {0, 0, 0, 1, 0, 0, 1, 0, 0, ~0u, 0, 0};
  return {ray.o.x, ray.o.y,  ray.o.z,  ray.tMin, ray.d.x, ray.d.y,
          ray.d.z, ray.time, ray.tMax, ~0u,      0,       0};
}

RTCRayHit toRtcRayHit(const Ray& ray, const EmbreeAccel::RayRange& range) {
  RTCRayHit rh;
  rh.ray = toRtcRay(ray, range);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

Hit fromRtcRayHit(const RTCRayHit& rh) {
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  // Embree's instance convention is Glint's: geomID inside the group, instID[0] in the world.
  return {rh.ray.tfar, rh.hit.u, rh.hit.v, rh.hit.geomID, rh.hit.primID, rh.hit.instID[0]};
}

}  // namespace

Hit EmbreeAccel::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = toRtcRayHit(ray, range_);
  rtcIntersect1(groupScenes_[0], &context, &rh);
  Hit hit = fromRtcRayHit(rh);
  intersectPlanes(scene_, ray, hit);
  return hit;
}

void EmbreeAccel::intersectCoherent(const Ray* rays, Hit* hits, size_t n) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  constexpr size_t kChunk = 256;  // bounded stack, and Embree's streams gain little beyond
  RTCRayHit rh[kChunk];
  for (size_t begin = 0; begin < n; begin += kChunk) {
    const size_t count = std::min(kChunk, n - begin);
    for (size_t i = 0; i < count; ++i) rh[i] = toRtcRayHit(rays[begin + i], range_);
    rtcIntersect1M(groupScenes_[0], &context, rh, static_cast<unsigned>(count), sizeof(RTCRayHit));
    for (size_t i = 0; i < count; ++i) hits[begin + i] = fromRtcRayHit(rh[i]);
    intersectPlanes(scene_, rays + begin, hits + begin, count);
  }
}

void EmbreeAccel::occludedCoherent(const Ray* rays, bool* blocked, size_t n) const {
  // A closest-hit stream: a ray is blocked when it hits anything before its tMax, as with
  // rtcOccluded1. Not rtcOccluded1M: as fast, but it hung inside Embree 3.13.5's AVX-512 packet
  // traversal of an instanced scene under ASan (docs/performance.md). Not intersectCoherent: planes
  // are tested first and no Hit is built, work a shadow ray does not need.
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  constexpr size_t kChunk = 256;
  RTCRayHit rh[kChunk];
  uint32_t index[kChunk];  // the ray of each stream slot: those a plane blocks are not traced
  for (size_t begin = 0; begin < n; begin += kChunk) {
    const size_t end = std::min(n, begin + kChunk);
    occludedByPlanes(scene_, rays + begin, blocked + begin, end - begin);
    unsigned m = 0;
    for (size_t i = begin; i < end; ++i) {
      if (blocked[i]) continue;
      index[m] = static_cast<uint32_t>(i);
      rh[m++] = toRtcRayHit(rays[i], range_);
    }
    if (m == 0) continue;
    rtcIntersect1M(groupScenes_[0], &context, rh, m, sizeof(RTCRayHit));
    for (unsigned k = 0; k < m; ++k)
      blocked[index[k]] = rh[k].hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }
}

bool EmbreeAccel::occluded(const Ray& ray) const {
  if (occludedByPlanes(scene_, ray)) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = toRtcRay(ray, range_);
  rtcOccluded1(groupScenes_[0], &context, &r);
  return r.tfar < 0;
}

}  // namespace glint
