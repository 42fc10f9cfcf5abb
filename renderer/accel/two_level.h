#pragma once
// What each of Glint's own structures (the reference BVH, the grid, the octree, the k-d tree)
// does alike around its traversal: it starts in the world group, leaves planes to the shared
// loop, and hands an instance's ray, in object space, to the traversal of the instanced group.
// `Structure` provides
//   template <bool AnyHit, class Counter>
//   bool traverse(groupId, ray, instId, hit, Counter count) const
// the closest (or, with AnyHit, any) hit in the group closer than hit.t, written to `hit`,
// calling count.step() for each node or cell it visits and count.test() for each primitive it
// tests.
#include <cstdint>

#include "accel/accelerator.h"
#include "accel/primitives.h"
#include "scene/scene.h"

namespace glint {

// What a traversal did for one ray, instanced groups included (planes, tested by the shared
// loop beside every structure, are not counted): the nodes or cells it visited — for the BVH
// every node whose box it tests, a box the ray misses included; for the grid, the octree and
// the k-d tree the cells or nodes it enters (for the octree's generate-and-test walk, every node
// of each descent from the root) — and the primitives it tested. The seeds' claims are
// about these (seed 002 eq. 9.1: k ≤ 1 + 7(R − 1) cells per ray for the grid of R = ⌈∛n⌉ cells
// per axis, O(∛n); about log n nodes for the hierarchies), and `glint bench --structures`
// reports them beside the time per ray.
struct TraversalCounts {
  uint64_t steps = 0, tests = 0;
};

// A render's traversal counts nothing: these calls compile away.
struct NoCount {
  void step() const {}
  void test() const {}
};
struct Count {
  TraversalCounts* counts;
  void step() const { ++counts->steps; }
  void test() const { ++counts->tests; }
};

// The closest hit with its traversal counted, which Glint's own structures offer (Embree's
// traversal is not ours to count).
class CountingTraversal {
 public:
  virtual Hit intersectCounting(const Ray& ray, TraversalCounts& counts) const = 0;

 protected:
  ~CountingTraversal() = default;
};

template <class Structure>
class TwoLevelAccelerator : public Accelerator, public CountingTraversal {
 public:
  Hit intersect(const Ray& ray) const final { return closest(ray, NoCount{}); }
  bool occluded(const Ray& ray) const final {
    if (occludedByPlanes(scene_, ray)) return true;
    Hit hit;
    return self().template traverse<true>(0, ray, kInvalidId, hit, NoCount{});
  }
  Hit intersectCounting(const Ray& ray, TraversalCounts& counts) const final {
    return closest(ray, Count{&counts});
  }

 protected:
  explicit TwoLevelAccelerator(const Scene& scene) : scene_(scene) {}

  // intersectPrimitive's way into an instance (accel/primitives.h): the closest hit in its
  // group, found by this structure's traversal of that group.
  template <class Counter>
  auto intoInstance(Counter count) const {
    return [this, count](const Instance& inst, const Ray& ray, uint32_t geom, Hit& hit) {
      return self().template traverse<false>(inst.groupId, inst.toObject(ray), geom, hit, count);
    };
  }

  // A cell's or leaf's candidate list: prims[refs[k]] for k in [0, n), tested in order. Whether
  // one was hit closer than hit.t (written to `hit`); with AnyHit, stops at the first.
  template <bool AnyHit, class Counter>
  bool testList(uint32_t groupId, const PrimitiveBox* prims, const uint32_t* refs, uint32_t n,
                const Ray& ray, uint32_t instId, Hit& hit, Counter count) const {
    bool found = false;
    for (uint32_t k = 0; k < n; ++k) {
      const PrimitiveBox& p = prims[refs[k]];
      count.test();
      if (intersectPrimitive(scene_, groupId, p.geom, p.prim, ray, instId, hit,
                             intoInstance(count))) {
        if constexpr (AnyHit) return true;
        found = true;
      }
    }
    return found;
  }

  const Scene& scene_;

 private:
  const Structure& self() const { return static_cast<const Structure&>(*this); }
  template <class Counter>
  Hit closest(const Ray& ray, Counter count) const {
    Hit hit;
    self().template traverse<false>(0, ray, kInvalidId, hit, count);
    intersectPlanes(scene_, ray, hit);
    return hit;
  }
};

}  // namespace glint
