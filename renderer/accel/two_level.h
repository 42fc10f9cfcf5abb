#pragma once
// What each of Glint's own structures (the reference BVH, the grid, the octree, the k-d tree)
// does alike around its traversal: it starts in the world group, leaves planes to the shared
// loop, and hands an instance's ray, in object space, to the traversal of the instanced group.
// `Structure` provides `template <bool AnyHit> bool traverse(groupId, ray, instId, hit) const`:
// the closest (or, with AnyHit, any) hit in the group closer than hit.t, written to `hit`.
#include "accel/accelerator.h"
#include "scene/scene.h"

namespace glint {

template <class Structure>
class TwoLevelAccelerator : public Accelerator {
 public:
  Hit intersect(const Ray& ray) const final {
    Hit hit;
    self().template traverse<false>(0, ray, kInvalidId, hit);
    intersectPlanes(scene_, ray, hit);
    return hit;
  }
  bool occluded(const Ray& ray) const final {
    if (occludedByPlanes(scene_, ray)) return true;
    Hit hit;
    return self().template traverse<true>(0, ray, kInvalidId, hit);
  }

 protected:
  explicit TwoLevelAccelerator(const Scene& scene) : scene_(scene) {}

  // intersectPrimitive's way into an instance (accel/primitives.h): the closest hit in its
  // group, found by this structure's traversal of that group.
  auto intoInstance() const {
    return [this](const Instance& inst, const Ray& ray, uint32_t geom, Hit& hit) {
      return self().template traverse<false>(inst.groupId, inst.toObject(ray), geom, hit);
    };
  }

  const Scene& scene_;

 private:
  const Structure& self() const { return static_cast<const Structure&>(*this); }
};

}  // namespace glint
