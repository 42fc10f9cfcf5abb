#pragma once
// The immutable scene every later stage reads: geometry in groups (group 0 is the world;
// others are placed by instances), materials, lights, camera and render settings.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "core/affine.h"
#include "core/bounds.h"
#include "core/motion.h"
#include "core/sampler.h"
#include "core/transform.h"
#include "geometry/csg.h"
#include "geometry/shading_point.h"
#include "geometry/shapes.h"
#include "geometry/triangle_mesh.h"
#include "lights/light.h"
#include "materials/material.h"
#include "scene/features.h"

namespace glint {

enum class GeomKind : uint8_t { Mesh, Sphere, Quad, Disk, Plane, Csg, Instance };

// One entry of a group. A hit's geomId is this entry's index in its group, so every backend
// reports the same ids.
struct Geometry {
  GeomKind kind = GeomKind::Mesh;
  uint32_t index = 0;       // into the scene's array for `kind`
  uint32_t materialId = 0;  // unused for instances; a CSG solid's surfaces carry their own
  // A world entry: its object id (Scene::objectNames). A group's member: its place in the
  // group (a hit inside an instance counts for the instance's object).
  uint32_t objectId = 0;
};

struct Instance {
  uint32_t groupId = 0;
  Transform worldFromObject;   // when static
  std::vector<TrsKey> motion;  // K ≥ 2 keys over [0, 1] when moving; empty when static

  // worldFromObject at normalised time (slerp for rotation, as Embree's quaternion motion).
  Transform transformAt(float time) const;
  // `ray` carried into the object's space at ray.time. As in Embree, the direction is not
  // renormalised, so t means the same distance along the ray in both spaces.
  Ray toObject(const Ray& ray) const;
  // Whether the keys turn the object (their rotations differ), so Embree's slerp is used.
  bool rotates() const {
    for (const TrsKey& k : motion)
      if (!(k.rotation == motion[0].rotation)) return true;
    return false;
  }
};

// Bound on the difference between Embree's interpolated rotation angle and ours, in radians
// (Scene::shadingPoint widens the error bound of points on turning instances by it).
inline constexpr float kSlerpAngleError = 2e-4f;

struct Group {
  std::string name;
  std::vector<Geometry> geometries;
};

struct RenderSettings {
  int width = 640, height = 480;
  int spp = 16;
  int maxDepth = 8;
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::Stratified;
  Rgb background;
  Rgb ambient;
  bool transparentShadows = false;
  // Camera rays that miss leave the pixel transparent (RGB 0, alpha 0) instead of showing the
  // background opaque; reflected and refracted rays still see the background.
  bool transparentBackground = false;
};

// An animated scene's frames, first … last, and the frame this Scene is (io/animation.h).
struct Animation {
  int first = 0, last = 0;
  int frame = 0;
};

class Scene {
 public:
  std::string sourcePath;   // the scene file, or "<default scene>"
  uint64_t sourceHash = 0;  // of the scene file's bytes
  RenderSettings render;
  CameraDesc cameraDesc;
  std::optional<Animation> animation;  // absent for a still scene
  // Everything below lives in render space: world space minus this point, the camera's eye
  // (io/placement.h). Add it back to name a world position.
  Vec3d worldOrigin;
  std::vector<Material> materials;
  std::vector<Light> lights;
  // The environment among the lights, copied (it shares its image) by the loader, which allows
  // one: what rays that leave the scene see in place of render.background.
  std::optional<EnvironmentLight> environment;
  // Per light, its "name" (a glTF light's own), empty when it has none; may be shorter than
  // `lights` in scenes built in code. lightName gives the name with its default.
  std::vector<std::string> lightNames;

  std::vector<Group> groups;  // groups[0] is the world
  // Per object id, the object's name, which Cryptomatte, the objectid manifest and --stats
  // show (docs/scene-format.md, Names): an object's "name", else "objects[i]"; a mesh file's
  // named parts; a visible light's surface. Names are unique: one name, one id. Scenes built
  // in code may leave it empty (objectName then names id i "objects[i]").
  std::vector<std::string> objectNames;
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  // Per sphere: centre keys over [0, 1] when it moves (seed 000 §13.4.5), else empty.
  std::vector<std::vector<Vec3f>> sphereCenterKeys;
  std::vector<Quad> quads;
  std::vector<Disk> disks;  // the surfaces of visible disk lights
  std::vector<Plane> planes;
  std::vector<CsgSolid> csgs;  // one primitive each: a ray meets the solid, not its operands
  // Per plane, its entry in groups[0] (planes live only there): every ray tests every plane
  // (accel/accelerator.h), and must not walk the whole world to find them.
  std::vector<uint32_t> planeGeometries;
  std::vector<Instance> instances;

  Features features;

  // What a ray leaving the scene along d (any length) sees (Trace's background): the
  // environment, else the background colour.
  Rgb background(const Vec3f& d) const {
    return environment ? environment->radiance(d) : render.background;
  }

  // Rebuilds the world-space surface point of a hit (DESIGN.md §3). Shared by all backends.
  ShadingPoint shadingPoint(const Ray& ray, const Hit& hit) const {
    ShadingPoint sp;
    shadingPoint(ray, hit, sp);
    return sp;
  }
  // The same written into `sp`, for callers that keep it (a returned copy stalled on store
  // forwarding).
  void shadingPoint(const Ray& ray, const Hit& hit, ShadingPoint& sp) const;
  // Bounds of everything finite in the world (planes excluded).
  Bounds3f worldBounds() const;
  Bounds3f groupBounds(uint32_t groupId) const;
  Bounds3f geometryBounds(const Geometry& g) const;  // empty for a plane
  size_t triangleCount() const;
  // Triangles, spheres, quads, disks, planes and CSG solids (instances not counted).
  size_t primitiveCount() const {
    return triangleCount() + spheres.size() + quads.size() + disks.size() + planes.size() +
           csgs.size();
  }

  // Whether a candidate hit at distance t along `ray` (in the space of g's group), on primitive
  // `prim` at (u, v) (Hit's conventions), falls in a hole of its material's cut-out
  // (materials/cutout.h). Every backend asks it of every candidate hit, so all agree on where
  // the holes are.
  bool cutAway(const Geometry& g, const Ray& ray, float t, uint32_t prim, float u, float v) const {
    return hasCutout(g) &&
           materials[g.materialId].cutout.holeAt(textureCoordinates(
               g, ray, t, prim, u, v, materials[g.materialId].cutout.uvTransform.uvSet));
  }
  // Whether g's material has a cut-out (only then do backends test its hits against it).
  bool hasCutout(const Geometry& g) const {
    return features.cutouts && materials[g.materialId].cutout.active();
  }

  const Geometry& geometry(const Hit& hit) const;
  // The object id of a hit: the top-level entry's (an instance's for a hit inside it), or the
  // triangle's where its mesh names its triangles' objects (TriangleMesh::objectIds).
  uint32_t objectId(const Hit& hit) const {
    const Geometry& g = geometry(hit);
    if (g.kind == GeomKind::Mesh && !meshes[g.index].objectIds.empty()) [[unlikely]]
      return meshes[g.index].objectIds[hit.primId];
    return groups[0].geometries[hit.instId != kInvalidId ? hit.instId : hit.geomId].objectId;
  }
  // Whether each object id is shown by something in the world (an id can be registered for an
  // object whose every triangle names another).
  std::vector<bool> objectIdsInWorld() const;
  std::string objectName(uint32_t id) const {
    return id < objectNames.size() ? objectNames[id] : "objects[" + std::to_string(id) + "]";
  }
  // Light K's "name", else "lights[K]".
  std::string lightName(size_t k) const {
    return k < lightNames.size() && !lightNames[k].empty() ? lightNames[k]
                                                           : "lights[" + std::to_string(k) + "]";
  }
  // The material of the surface hit: the geometry's, or on a CSG solid its operand's.
  uint32_t materialId(const Hit& hit) const {
    const Geometry& g = geometry(hit);
    if (g.kind != GeomKind::Csg) [[likely]]
      return g.materialId;
    const CsgSolid& solid = csgs[g.index];
    return solid.leaves[solid.surface(hit.primId).leaf].materialId;
  }
  Sphere sphereAt(uint32_t index, float time) const;
  // Time steps the accelerators need for a geometry entry: 1 when static.
  size_t timeSteps(const Geometry& g) const;

 private:
  // shadingPoint for a hit in object space, placed in the world by `worldFromObject` (null
  // outside instances). Two copies: the world's hits, the most, take one without the transform.
  template <bool kInstanced>
  void shadingPoint(const Ray& ray, const Hit& hit, const Transform* worldFromObject,
                    ShadingPoint& sp) const;
  // shadingPoint for a hit on a world entry that is a static flat mesh, a static sphere or a
  // plane, the most common hits, in SSE lanes; false (and nothing written) for any other.
  bool worldPointInLanes(const Ray& ray, const Hit& hit, ShadingPoint& sp) const;
  // Holds worldPointInLanes to shadingPoint<false>'s bits (tests/scene/world_point_lanes_test.cpp).
  friend struct WorldPointPaths;
  // shadingPoint for a hit inside an instance. Out of line, as the general form, so that the
  // common hits do not set up the transform or save the registers it uses.
  [[gnu::noinline]] void instancePoint(const Ray& ray, const Hit& hit, ShadingPoint& sp) const;
  // What shadingPoint adds last where the scene uses them: texture coordinates and tangents
  // (for a hit at object-space point pObject) and the vertex colour. Out of line, so that a hit
  // without them does not save its registers.
  [[gnu::noinline]] void addSurfaceData(const Geometry& g, const Hit& hit, const Vec3f& pObject,
                                        float time, const Transform* worldFromObject,
                                        ShadingPoint& sp) const;
  // sp's texture coordinates and tangents for a hit at object-space point p (ShadingPoint::uv).
  void surfaceCoordinates(const Geometry& g, const Hit& hit, const Vec3f& p, float time,
                          const Transform* worldFromObject, ShadingPoint& sp) const;
  // sp's tangent frame for normal maps (ShadingPoint::tangent), after its tangents dp/du, dp/dv.
  void tangentFrame(const Geometry& g, const Hit& hit, const Transform* worldFromObject,
                    ShadingPoint& sp) const;
  // The (u, v) of a hit at object-space point p in the coordinate set `set` (1: a mesh's
  // second set, where it has one; every other surface has only the first), and the object-space
  // tangents dp/du, dp/dv where `dpdu` is not null.
  Vec2f uvAt(const Geometry& g, const Hit& hit, const Vec3f& p, float time, Vec3f* dpdu,
             Vec3f* dpdv, int set = 0) const;
  // The (u, v) of a candidate hit (cutAway's arguments), without a ShadingPoint.
  Vec2f textureCoordinates(const Geometry& g, const Ray& ray, float t, uint32_t prim, float u,
                           float v, int set) const;
  // The interpolated vertex normal at a hit on a smooth mesh, in world space, unit, on the side
  // of the geometric normal `ng` (which secondary rays leave from: no shadow terminator).
  static Vec3f smoothNormal(const TriangleMesh& m, const Hit& hit, const Transform* worldFromObject,
                            const Vec3f& ng);
};

}  // namespace glint
