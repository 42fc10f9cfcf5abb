#pragma once
// Embree 3 backend: one RTCScene per group, groups placed by Embree instances (shared, not
// copied), triangle meshes shared with Embree without copying, spheres and quads as user
// geometry calling the shared intersection routines of geometry/shapes.h. Geometries whose
// material has an opacity cut-out pass over hits in its holes (filter functions for triangles).
#include <embree3/rtcore.h>

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
  // n closest hits through Embree's stream API (rtcIntersect1M); `coherent` tells Embree the
  // rays start close together and point alike (camera rays), so it traces them as packets.
  void intersectStream(const Ray* rays, Hit* hits, size_t n, bool coherent) const;
  void intersectCoherent(const Ray* rays, Hit* hits, size_t n) const override {
    intersectStream(rays, hits, n, true);
  }
  void occludedCoherent(const Ray* rays, bool* blocked, size_t n) const override;
  std::string_view name() const override { return "embree"; }
  double buildSeconds() const { return buildSeconds_; }
  int64_t bytes() const { return bytes_; }

  struct UserShape;  // what a user-geometry or cut-out filter callback needs, owned here

 private:
  RTCScene buildGroup(uint32_t groupId);
  void addGeometries(RTCScene rtcScene, uint32_t groupId);

  const Scene& scene_;
  std::vector<RTCScene> groupScenes_;  // index = group id; [0] is the world
  std::vector<std::unique_ptr<UserShape>> userShapes_;
  double buildSeconds_ = 0;
  int64_t bytes_ = 0;
};

}  // namespace glint
