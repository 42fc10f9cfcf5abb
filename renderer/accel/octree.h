#pragma once
// The octree of seed 002 §9.2.2: the cube around a group cut into eight congruent cells, and
// only the *partial* cells (those some primitive's box reaches) cut again, down to
// K = ⌈log₂(n)/3⌉ levels (a cell of the finest level is a cell of seed 002's R = ⌈∛n⌉ grid), or
// until a cell holds at most two primitives. Empty cells are leaves with nothing in them.
// A ray visits the leaves it crosses front to back: in a cell it crosses the three mid-planes
// in order of their distance along the ray, and each crossing moves it to the octant across
// that plane (instead of the seed's generate-and-test point location: the same cells in the
// same order, without descending from the root for each). Two levels like the reference BVH:
// an instance is a primitive of its parent's octree and has an octree of its own group.
#include <cstdint>
#include <vector>

#include "accel/primitives.h"
#include "accel/two_level.h"

namespace glint {

class Octree final : public TwoLevelAccelerator<Octree> {
 public:
  // `levels` of subdivision for every group; 0: K = ⌈log₂(n)/3⌉ for a group of n primitives.
  explicit Octree(const Scene& scene, int levels = 0);
  std::string_view name() const override { return "octree"; }
  const SubdivisionStats& stats() const { return stats_; }

  struct Node {
    uint32_t firstChild = kInvalidId;  // eight consecutive nodes, octant bits x = 1, y = 2, z = 4
    uint32_t refStart = 0, refCount = 0;  // a leaf's primitives: refs[refStart, + refCount)
  };
  struct Tree {
    Bounds3f box;                // of the group's primitives
    Vec3f center;                // of the root cube around it
    float half = 0;              // half its side
    std::vector<Node> nodes;     // nodes[0] is the root
    std::vector<uint32_t> refs;  // indices into prims
    std::vector<PrimitiveBox> prims;
  };

 private:
  friend class TwoLevelAccelerator<Octree>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;

  std::vector<Tree> trees_;  // one per group
  SubdivisionStats stats_;
};

}  // namespace glint
