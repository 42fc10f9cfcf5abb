#pragma once
// Glint's own BVH2, the reference that checks Embree hit by hit (DESIGN.md §3–4). One tree per
// group, two levels like Embree's instancing. Builds: binned SAH (16 bins, ≤ 4 primitives per
// leaf; Wald 2007), and the object-median and spatial-midpoint splits of seed 000 §12.3.2 for
// comparison. Traversal is ordered (near child first) with a slab test that survives ±0
// direction components and pads by 2 ulps (Ize 2013); primitives use the same intersection
// routines as every other backend, the watertight triangle test among them.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "accel/two_level.h"
#include "core/bounds.h"

namespace glint {

enum class BvhSplit { Sah, Median, Midpoint };
std::string_view bvhSplitName(BvhSplit);

struct BvhStats {
  double buildSeconds = 0;
  size_t nodes = 0, leaves = 0, primitives = 0, maxDepth = 0;
  double sahCost = 0;  // traversal cost 1, intersection cost 1, relative to the root's area
  size_t bytes = 0;
  double primitivesPerLeaf() const { return leaves ? double(primitives) / double(leaves) : 0; }
};

class ReferenceBvh final : public TwoLevelAccelerator<ReferenceBvh> {
 public:
  static constexpr int kMaxLeafSize = 4;
  static constexpr int kBins = 16;
  static constexpr size_t kMaxDepth = 128;

  ReferenceBvh(const Scene& scene, BvhSplit split = BvhSplit::Sah);
  std::string_view name() const override { return "bvh"; }

  const BvhStats& stats() const { return stats_; }

  // Checks the tree invariants: every child box inside its parent, every primitive of every
  // group in exactly one leaf, every leaf box containing its primitives. Returns an empty
  // string when they hold, else the first violation.
  std::string checkInvariants() const;

  struct Node {
    Bounds3f box;
    uint32_t first = 0;  // leaf: first primitive index; inner: index of the second child
    uint16_t count = 0;  // leaf: primitive count; 0 for inner nodes (first child is next)
    uint16_t axis = 0;   // inner: split axis, for near-first ordering
  };
  struct PrimRef {
    uint32_t geom = 0;  // index in the group
    uint32_t prim = 0;  // triangle index, or 0
  };
  struct Tree {
    std::vector<Node> nodes;
    std::vector<PrimRef> prims;
    // Corners of static triangles in leaf order, so leaves read contiguous memory instead of
    // chasing group → mesh → index → vertex; `staticTriangle[i]` says whether slot i has them.
    std::vector<std::array<Vec3f, 3>> corners;
    std::vector<uint8_t> staticTriangle;
  };

 private:
  friend class TwoLevelAccelerator<ReferenceBvh>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;
  template <class Counter>
  bool intersectPrim(uint32_t groupId, uint32_t slot, const Ray& ray, uint32_t instId, Hit& hit,
                     Counter count) const;

  std::vector<Tree> trees_;  // one per group
  BvhStats stats_;
};

}  // namespace glint
