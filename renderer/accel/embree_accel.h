#pragma once
// Embree 3 backend: one RTCScene per group, groups placed by Embree instances (shared, not
// copied), triangle meshes shared with Embree without copying, spheres and quads as user
// geometry calling the shared intersection routines of geometry/shapes.h. Geometries whose
// material has an opacity cut-out pass over hits in its holes (filter functions for triangles).
#include <embree3/rtcore.h>

#include <cmath>
#include <vector>

#include "accel/accelerator.h"

namespace glint {

// One Embree device per process. Embree reports errors through a callback; we record the
// message there and throw it as a GlintError after the call (throwing through C is undefined).
RTCDevice embreeDevice();
void throwIfEmbreeFailed(const char* what);
std::string embreeVersionString();
// Bytes Embree holds, as reported to its memory monitor (BVHs and internal buffers; shared
// geometry buffers are ours and not counted).
int64_t embreeMemoryBytes();

class EmbreeAccel final : public Accelerator {
 public:
  explicit EmbreeAccel(const Scene& scene);
  ~EmbreeAccel() override;
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  // n closest hits through Embree's stream API (rtcIntersect1M), flagged coherent: the rays start
  // close together and point alike (a chunk's camera rays, or the rays its hits spawn), so Embree
  // traces them as packets.
  void intersectCoherent(const Ray* rays, Hit* hits, size_t n) const override;
  void occludedCoherent(const Ray* rays, bool* blocked, size_t n) const override;
  std::string_view name() const override { return "embree"; }
  double buildSeconds() const { return buildSeconds_; }
  int64_t bytes() const { return bytes_; }

  struct UserShape;  // what a user-geometry or cut-out filter callback needs, owned here

  // The rays Embree is given: each coordinate of the origin and direction within these, in the
  // world and, carried by the scene's instances, in every instance's space (core/ray.h says
  // what Embree asserts). A ray outside them is not traced by Embree (it misses what Embree
  // holds); the loaders keep every ray a scene makes inside them.
  struct RayRange {
    float origin = kEmbreeMaxRayCoordinate, direction = kEmbreeMaxRayCoordinate;
    bool takes(const Ray& r) const {
      return std::fabs(r.o.x) <= origin && std::fabs(r.o.y) <= origin &&
             std::fabs(r.o.z) <= origin && std::fabs(r.d.x) <= direction &&
             std::fabs(r.d.y) <= direction && std::fabs(r.d.z) <= direction && r.tMin >= 0 &&
             r.tMax <= kInfinity && r.time >= 0 && r.time <= 1;
    }
  };
  const RayRange& rayRange() const { return range_; }

 private:
  RTCScene buildGroup(uint32_t groupId);
  void addGeometries(RTCScene rtcScene, uint32_t groupId);

  const Scene& scene_;
  std::vector<RTCScene> groupScenes_;  // index = group id; [0] is the world
  std::vector<std::unique_ptr<UserShape>> userShapes_;
  double buildSeconds_ = 0;
  int64_t bytes_ = 0;
  RayRange range_;
};

// The range of rays Embree accepts for `scene`: kEmbreeMaxRayCoordinate with a margin for
// rounding, divided by the most any instance's inverse transform (at any key) can grow a
// coordinate, less what its translation adds.
EmbreeAccel::RayRange embreeRayRange(const Scene& scene);

}  // namespace glint
