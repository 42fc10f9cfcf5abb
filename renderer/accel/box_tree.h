#pragma once
// A BVH over a list of primitive boxes: the object median on the longest axis of the boxes'
// centres (seed 000 §12.3.2), at most four primitives to a leaf, children visited near one
// first. Ray coherence (accel/ray_coherence.h) keeps one inside each mesh object, one per
// instanced group, and one over the world for the rays it cannot classify.
#include <cstdint>
#include <vector>

#include "accel/primitives.h"
#include "core/slab_test.h"

namespace glint {

class BoxTree {
 public:
  BoxTree() = default;
  explicit BoxTree(std::vector<PrimitiveBox> prims);

  bool empty() const { return prims_.empty(); }
  const Bounds3f& box() const { return box_; }
  const std::vector<PrimitiveBox>& primitives() const { return prims_; }
  size_t bytes() const {
    return nodes_.size() * sizeof(Node) + prims_.size() * sizeof(PrimitiveBox);
  }

  // Calls test(primitive) for each primitive whose leaf the ray reaches before min(ray.tMax,
  // hit.t), `hit` being what the tests write their hits to; with AnyHit, stops at the first
  // test that returns true. count.step() for each node whose box is tested.
  template <bool AnyHit, class Test, class Counter>
  bool traverse(const Ray& ray, const Hit& hit, Test&& test, Counter count) const;

 private:
  struct Node {
    Bounds3f box;
    uint32_t first = 0;  // leaf: first primitive; inner: the second child (the first is next)
    uint32_t count = 0;  // leaf: primitives; 0 for an inner node
    uint32_t axis = 0;   // inner: the split axis
  };
  void build(size_t begin, size_t end);

  Bounds3f box_;
  std::vector<Node> nodes_;
  std::vector<PrimitiveBox> prims_;
};

template <bool AnyHit, class Test, class Counter>
bool BoxTree::traverse(const Ray& ray, const Hit& hit, Test&& test, Counter count) const {
  if (nodes_.empty()) return false;
  const RaySlabs slabs(ray);
  // Median splits keep the depth at log2 of the primitives (under 64 for any count held).
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  bool found = false;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    count.step();
    float t0 = ray.tMin, t1 = std::min(ray.tMax, hit.t);
    if (!slabTest(n.box, ray, slabs, t0, t1)) continue;
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i)
        if (test(prims_[i])) {
          if constexpr (AnyHit) return true;
          found = true;
        }
      continue;
    }
    const auto self = static_cast<uint32_t>(&n - nodes_.data());
    // The near child on top.
    if (slabs.negative[n.axis]) {
      stack[top++] = self + 1;
      stack[top++] = n.first;
    } else {
      stack[top++] = n.first;
      stack[top++] = self + 1;
    }
  }
  return found;
}

}  // namespace glint
