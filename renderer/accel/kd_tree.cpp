#include "accel/kd_tree.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "core/seconds_since.h"

namespace glint {

namespace {

constexpr int kBins = 32;
// Relative costs of a traversal step and of one primitive test, and the share of the
// primitives' cost a split saves when one side is empty (it cuts empty space off the ray).
constexpr float kTraversalCost = 1, kIntersectionCost = 4, kEmptyBonus = 0.5f;
constexpr size_t kMaxDepth = 60;  // the traversal's stack holds this many pending sides
// A primitive whose box comes within this share of the node's extent of the plane is listed on
// both sides: a ray computed a hair across the plane must still find it.
constexpr float kPlanePad = 1e-5f;

float halfArea(const Bounds3f& b) {
  const Vec3f d = b.hi - b.lo;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

struct Split {
  float cost = kInfinity;
  int axis = -1;
  float plane = 0;
};

class KdTreeBuilder {
 public:
  KdTreeBuilder(KdTree::Tree& tree)
      : t_(tree),
        budget_(referenceBudget(tree.prims.size())),
        references_(double(tree.prims.size())),
        depthLimit_(std::min(kMaxDepth, size_t(8 + 1.3 * std::log2(double(tree.prims.size()))))) {}

  void build(uint32_t node, const Bounds3f& box, const std::vector<uint32_t>& list, size_t depth,
             size_t& maxDepth) {
    maxDepth = std::max(maxDepth, depth);
    const Split best = depth < depthLimit_ && list.size() > 1 ? bestSplit(box, list) : Split{};
    // A split whose expected cost is no lower than testing everything here is not worth a node.
    if (best.axis >= 0 && best.cost < kIntersectionCost * float(list.size())) {
      const int a = best.axis;
      const float pad = kPlanePad * (box.hi[a] - box.lo[a]);
      std::vector<uint32_t> below, above;
      for (uint32_t i : list) {
        const Bounds3f& b = t_.prims[i].box;
        if (b.lo[a] <= best.plane + pad) below.push_back(i);
        if (b.hi[a] >= best.plane - pad) above.push_back(i);
      }
      const double growth = double(below.size() + above.size()) - double(list.size());
      if (references_ + growth <= budget_) {
        references_ += growth;
        t_.nodes[node].axis = uint32_t(a);
        t_.nodes[node].split = best.plane;
        Bounds3f belowBox = box, aboveBox = box;
        belowBox.hi[a] = best.plane;
        aboveBox.lo[a] = best.plane;
        t_.nodes.emplace_back();  // node + 1: the side below
        build(node + 1, belowBox, below, depth + 1, maxDepth);
        const auto aboveIndex = static_cast<uint32_t>(t_.nodes.size());
        t_.nodes.emplace_back();
        t_.nodes[node].first = aboveIndex;
        build(aboveIndex, aboveBox, above, depth + 1, maxDepth);
        return;
      }
    }
    t_.nodes[node].first = static_cast<uint32_t>(t_.refs.size());
    t_.nodes[node].count = static_cast<uint32_t>(list.size());
    t_.refs.insert(t_.refs.end(), list.begin(), list.end());
  }

 private:
  // The SAH's best plane among kBins − 1 evenly spaced ones per axis, with the primitives'
  // boxes clipped to the node.
  Split bestSplit(const Bounds3f& box, const std::vector<uint32_t>& list) const {
    Split best;
    const float area = halfArea(box);
    if (!(area > 0) || !std::isfinite(area)) return best;
    const float n = float(list.size());
    for (int a = 0; a < 3; ++a) {
      const float lo = box.lo[a], extent = box.hi[a] - lo;
      if (!(extent > 0)) continue;
      std::array<int, kBins> starts{}, ends{};
      const auto bin = [&](float x) {
        const float f = (std::clamp(x, lo, box.hi[a]) - lo) / extent * kBins;
        return std::min(static_cast<int>(f), kBins - 1);
      };
      for (uint32_t i : list) {
        ++starts[size_t(bin(t_.prims[i].box.lo[a]))];
        ++ends[size_t(bin(t_.prims[i].box.hi[a]))];
      }
      int below = 0, endedBelow = 0;
      for (int k = 1; k < kBins; ++k) {
        below += starts[size_t(k - 1)];     // begin below the plane
        endedBelow += ends[size_t(k - 1)];  // end below it: the rest reach above
        const float plane = lo + extent * float(k) / kBins;
        Bounds3f belowBox = box, aboveBox = box;
        belowBox.hi[a] = plane;
        aboveBox.lo[a] = plane;
        const float nBelow = float(below), nAbove = n - float(endedBelow);
        const float bonus = nBelow == 0 || nAbove == 0 ? kEmptyBonus : 0;
        const float cost = kTraversalCost + kIntersectionCost * (1 - bonus) *
                                                (halfArea(belowBox) / area * nBelow +
                                                 halfArea(aboveBox) / area * nAbove);
        if (cost < best.cost) best = {cost, a, plane};
      }
    }
    return best;
  }

  KdTree::Tree& t_;
  double budget_;
  double references_;  // in all lists made so far (the root's n to begin with)
  size_t depthLimit_;
};

}  // namespace

KdTree::KdTree(const Scene& scene) : TwoLevelAccelerator(scene) {
  const auto start = std::chrono::steady_clock::now();
  trees_.resize(scene.groups.size());
  // Instanced groups first (they follow their parents): an instance's box is its group's box.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    Tree& t = trees_[g];
    t.prims =
        groupPrimitives(scene, uint32_t(g), [&](uint32_t child) { return trees_[child].box; });
    if (t.prims.empty()) continue;
    for (const PrimitiveBox& p : t.prims) t.box.extend(p.box);
    std::vector<uint32_t> all(t.prims.size());
    for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    t.nodes.resize(1);
    KdTreeBuilder(t).build(0, t.box, all, 0, stats_.maxDepth);
    stats_.primitives += t.prims.size();
    stats_.references += t.refs.size();
    stats_.nodes += t.nodes.size();
    for (const Node& n : t.nodes) stats_.leaves += n.leaf();
    stats_.bytes += t.nodes.size() * sizeof(Node) + t.refs.size() * sizeof(uint32_t) +
                    t.prims.size() * sizeof(PrimitiveBox);
  }
  stats_.buildSeconds = secondsSince(start);
}

template <bool AnyHit, class Counter>
bool KdTree::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                      Counter count) const {
  const Tree& t = trees_[groupId];
  if (t.prims.empty()) return false;
  const RaySlabs slabs(ray);
  float t0 = ray.tMin, t1 = std::min(ray.tMax, hit.t);
  if (!slabTest(t.box, ray, slabs, t0, t1)) return false;
  struct Pending {
    uint32_t node;
    float t0, t1;
  };
  Pending stack[kMaxDepth + 1];
  int top = 0;
  uint32_t node = 0;
  bool found = false;
  while (true) {
    // What is left of the ray starts beyond the closest hit: nothing there is closer.
    if (found && hit.t < t0) break;
    const Node& n = t.nodes[node];
    count.step();
    if (!n.leaf()) {
      // Seed 000 §12.3.4's four cases: the ray meets only the near side (the plane lies beyond
      // the segment or behind the origin), only the far side (the plane lies before the
      // segment), or both, near first. A NaN distance (origin on a plane the ray runs along)
      // fails every comparison and visits both.
      const int a = int(n.axis);
      const float tPlane = (n.split - ray.o[a]) * slabs.inv[a];
      const bool belowFirst = ray.o[a] < n.split || (ray.o[a] == n.split && ray.d[a] <= 0);
      const uint32_t nearSide = belowFirst ? node + 1 : n.first;
      const uint32_t farSide = belowFirst ? n.first : node + 1;
      if (tPlane > t1 || tPlane <= 0) {
        node = nearSide;
      } else if (tPlane < t0) {
        node = farSide;
      } else {
        stack[top++] = {farSide, tPlane, t1};
        node = nearSide;
        t1 = tPlane;
      }
      continue;
    }
    if (testList<AnyHit>(groupId, t.prims.data(), t.refs.data() + n.first, n.count, ray, instId,
                         hit, count)) {
      if constexpr (AnyHit) return true;
      found = true;
    }
    if (top == 0) break;
    --top;
    node = stack[top].node;
    t0 = stack[top].t0;
    t1 = stack[top].t1;
  }
  return found;
}

}  // namespace glint
