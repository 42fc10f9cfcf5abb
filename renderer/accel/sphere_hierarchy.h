#pragma once
// A hierarchy of bounding spheres (seed 001 §9, advice 8: "a ray must first intersect an
// object's bounding sphere, before the actual object geometry is used ... Hierarchies of
// bounding spheres can be used for very complex models"). One tree per group, two levels like
// the reference BVH. Build: binned SAH over primitive boxes as the reference BVH's, on the
// longest centroid axis only (16 bins, ≤ 4 primitives per leaf; an object-median split below
// depth 64, which bounds the depth by 64 + log₂ n). Every primitive gets its own bounding sphere (a
// static triangle the smaller of its box's sphere and the sphere about its vertices' mean; anything
// else its shutter box's sphere; a static sphere is its own bound and is not tested twice); a
// leaf's sphere encloses its primitives' spheres, an inner node's its two children's spheres,
// each the smaller of the exact sphere around the spheres it encloses and the one centred on the
// node's box. Traversal tests both children's spheres, descends into the nearer entry first and
// drops any sphere entered beyond the closest hit so far.
#include <cstdint>
#include <string>
#include <vector>

#include "accel/primitives.h"
#include "accel/two_level.h"
#include "geometry/shapes.h"

namespace glint {

class SphereHierarchy final : public TwoLevelAccelerator<SphereHierarchy> {
 public:
  static constexpr int kMaxLeafSize = 4;
  static constexpr int kBins = 16;
  static constexpr size_t kMedianBelowDepth = 64;
  static constexpr size_t kMaxDepth = 128;

  explicit SphereHierarchy(const Scene& scene);
  std::string_view name() const override { return "spheres"; }
  // references: primitives (each is in one leaf).
  const SubdivisionStats& stats() const { return stats_; }

  // The sphere of group `groupId`'s root (radius −1 when the group has nothing bounded).
  Sphere rootSphere(uint32_t groupId) const;

  // Checks the tree: every inner node's sphere encloses its children's, every leaf's encloses
  // its primitives' spheres, each primitive's sphere encloses its triangle's corners or its box,
  // and every primitive is in exactly one leaf. Empty when that holds, else the first violation.
  std::string checkInvariants() const;

  struct Node {
    Sphere bound;
    uint32_t first = 0;  // leaf: first primitive slot; inner: index of the second child
    uint32_t count = 0;  // leaf: primitive count; 0 for inner nodes (first child is next)
  };
  struct Slot {
    Sphere bound;
    uint32_t geom = 0, prim = 0;
    bool exact = false;  // the bound is the object (a static sphere): not tested first
  };
  struct Tree {
    std::vector<Node> nodes;
    std::vector<Slot> slots;
    Bounds3f box;  // the group's, over the shutter: an instance of it is bounded by it
  };
  const Tree& tree(uint32_t groupId) const { return trees_[groupId]; }

 private:
  friend class TwoLevelAccelerator<SphereHierarchy>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;

  std::vector<Tree> trees_;  // one per group
  SubdivisionStats stats_;
};

}  // namespace glint
