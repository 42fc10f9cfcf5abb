#pragma once
// The oracle: a plain O(N) loop over every primitive (seed 000 §4.4.4), with the shared
// intersection routines. Slow by design; used to check the fast backends on small scenes.
#include "accel/accelerator.h"

namespace glint {

class BruteForce final : public Accelerator {
 public:
  explicit BruteForce(const Scene& scene) : scene_(scene) {}
  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "brute"; }

 private:
  // Nearest hit of group `groupId` closer than hit.t for a ray already in that group's space;
  // false when there is none.
  bool intersectGroup(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit) const;
  const Scene& scene_;
};

}  // namespace glint
