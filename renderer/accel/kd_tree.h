#pragma once
// The axis-aligned BSP tree (k-d tree) of seed 000 §12.3.4: each inner node cuts its box by one
// plane perpendicular to an axis, a primitive whose box straddles the plane is listed on both
// sides, and a ray visits the sides in the order it crosses them, skipping the side it does not
// reach (the seed's four cases). The plane is chosen by the surface area heuristic over 32
// candidate positions per axis (primitive boxes clipped to the node), as a leaf's cost
// is weighed against the split's (MacDonald and Booth 1990; pbrt-v3's termination and depth
// bound 8 + 1.3·log₂ n). Two levels like the reference BVH: an instance is a primitive of its
// parent's tree and has a tree of its own group.
#include <cstdint>
#include <vector>

#include "accel/primitives.h"
#include "accel/two_level.h"

namespace glint {

class KdTree final : public TwoLevelAccelerator<KdTree> {
 public:
  explicit KdTree(const Scene& scene);
  std::string_view name() const override { return "kdtree"; }
  const SubdivisionStats& stats() const { return stats_; }

  struct Node {
    float split = 0;
    uint32_t axis = 3;  // 0, 1, 2: an inner node; 3: a leaf
    // Inner: the child above the plane (the one below is the next node). Leaf: its primitives
    // are refs[first, first + count).
    uint32_t first = 0, count = 0;
    bool leaf() const { return axis == 3; }
  };
  struct Tree {
    Bounds3f box;
    std::vector<Node> nodes;  // nodes[0] is the root
    std::vector<uint32_t> refs;
    std::vector<PrimitiveBox> prims;
  };

 private:
  friend class TwoLevelAccelerator<KdTree>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;

  std::vector<Tree> trees_;  // one per group
  SubdivisionStats stats_;
};

}  // namespace glint
