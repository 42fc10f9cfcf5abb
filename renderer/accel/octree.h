#pragma once
// The octree of seed 002 §9.2.2: the cube around a group cut into eight congruent cells, and
// only the *partial* cells (those some primitive's surface meets, accel/surface_cell_overlap.h)
// cut again, down to K = ⌈log₂(n)/3⌉ levels (a cell of the finest level is a cell of seed 002's
// R = ⌈∛n⌉ grid), or until a cell holds at most two primitives. A cell no surface meets is a
// leaf with nothing in it, whether it is empty or full (inside a solid): the seed's null child.
// Two walks find the leaves a ray crosses, front to back (the mid-plane walk is the default, the
// faster of the two on the study's scenes, docs/acceleration.md):
// - generate-and-test (the seed's, after Glassner 1984): Classify the ray's first point from
//   the root down to its leaf; from the point e where the ray leaves that leaf, q = e + (b/2)·
//   (the axes of the faces it leaves by) of eq. 9.18, b the smallest cell's side, is Classified
//   again, until the closest hit lies in the current leaf or the ray leaves the cube;
// - mid-plane: in a cell the ray crosses the three mid-planes in order of their distance along
//   it, each crossing moving it to the octant across that plane (the same leaves in the same
//   order, without descending from the root for each).
// Two levels like the reference BVH: an instance is a primitive of its parent's octree and has
// an octree of its own group.
#include <cstdint>
#include <vector>

#include "accel/primitives.h"
#include "accel/two_level.h"

namespace glint {

class Octree final : public TwoLevelAccelerator<Octree> {
 public:
  enum class Walk { GenerateAndTest, MidPlane };
  // `levels` of subdivision for every group; 0: K = ⌈log₂(n)/3⌉ for a group of n primitives.
  explicit Octree(const Scene& scene, int levels = 0, Walk walk = Walk::MidPlane);
  std::string_view name() const override {
    return walk_ == Walk::GenerateAndTest ? "octree-generate-and-test" : "octree";
  }
  const SubdivisionStats& stats() const { return stats_; }

  struct Node {
    uint32_t firstChild = kInvalidId;  // eight consecutive nodes, octant bits x = 1, y = 2, z = 4
    uint32_t refStart = 0, refCount = 0;  // a leaf's primitives: refs[refStart, + refCount)
  };
  struct Tree {
    Bounds3f box;                // of the group's primitives
    Vec3f center;                // of the root cube around it
    float half = 0;              // half its side
    Bounds3f cube;               // the root cube, center ± half
    float step = 0;              // half the side of a cell of the finest level (b/2 of eq. 9.18)
    std::vector<Node> nodes;     // nodes[0] is the root
    std::vector<uint32_t> refs;  // indices into prims
    std::vector<PrimitiveBox> prims;
  };

 private:
  friend class TwoLevelAccelerator<Octree>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;
  template <bool AnyHit, class Counter>
  bool walkMidPlanes(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                     Counter count) const;
  template <bool AnyHit, class Counter>
  bool generateAndTest(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                       Counter count) const;
  // Tests the primitives of leaf `node` of group `groupId`'s tree; true when one is hit.
  template <bool AnyHit, class Counter>
  bool testLeaf(uint32_t groupId, uint32_t node, const Ray& ray, uint32_t instId, Hit& hit,
                Counter count) const;

  std::vector<Tree> trees_;  // one per group
  SubdivisionStats stats_;
  Walk walk_;
};

}  // namespace glint
