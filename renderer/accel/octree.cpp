#include "accel/octree.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace glint {

namespace {

// A cell stops being cut when it holds this few primitives: eight more cells would cost more
// steps than the tests they save.
constexpr size_t kLeafPrimitives = 2;
// 2^10 cells per axis at the finest level at most, as the uniform grid's resolution.
constexpr int kMaxLevels = 10;
// A primitive goes into every octant its box reaches, and this share of the cell beyond: a ray
// computed a hair across a mid-plane must still find it.
constexpr float kCellPad = 1e-4f;

class Builder {
 public:
  Builder(Octree::Tree& tree, int levels)
      : t_(tree),
        levels_(levels),
        budget_(referenceBudget(tree.prims.size())),
        references_(double(tree.prims.size())) {}

  void build(uint32_t node, const Vec3f& center, float half, std::vector<uint32_t> list, int depth,
             size_t& maxDepth) {
    maxDepth = std::max(maxDepth, size_t(depth));
    if (depth < levels_ && list.size() > kLeafPrimitives) {
      // The octants each primitive's box reaches (seed 002's "partial" cells).
      std::array<std::vector<uint32_t>, 8> octants;
      const float pad = kCellPad * half;
      size_t listed = 0;
      for (uint32_t i : list) {
        const Bounds3f& b = t_.prims[i].box;
        for (int k = 0; k < 8; ++k) {
          bool reaches = true;
          for (int a = 0; a < 3 && reaches; ++a)
            reaches = (k >> a & 1) ? b.hi[a] >= center[a] - pad : b.lo[a] <= center[a] + pad;
          if (reaches) octants[size_t(k)].push_back(i), ++listed;
        }
      }
      // Cutting pays only when it separates something, and only within the reference budget
      // (counted over every list, finished or not, so the bound holds for the whole tree).
      const double growth = double(listed) - double(list.size());
      if (listed < 8 * list.size() && references_ + growth <= budget_) {
        references_ += growth;
        const auto first = static_cast<uint32_t>(t_.nodes.size());
        t_.nodes.resize(first + 8);
        t_.nodes[node].firstChild = first;
        for (int k = 0; k < 8; ++k) {
          const Vec3f offset{(k & 1) ? half / 2 : -half / 2, (k & 2) ? half / 2 : -half / 2,
                             (k & 4) ? half / 2 : -half / 2};
          build(first + uint32_t(k), center + offset, half / 2, std::move(octants[size_t(k)]),
                depth + 1, maxDepth);
        }
        return;
      }
    }
    t_.nodes[node].refStart = static_cast<uint32_t>(t_.refs.size());
    t_.nodes[node].refCount = static_cast<uint32_t>(list.size());
    t_.refs.insert(t_.refs.end(), list.begin(), list.end());
  }

 private:
  Octree::Tree& t_;
  int levels_;
  double budget_;
  double references_;  // in all lists made so far (the root's n to begin with)
};

Octree::Tree buildTree(std::vector<PrimitiveBox> prims, int levels, size_t& maxDepth) {
  Octree::Tree t;
  Bounds3f& box = t.box;
  for (const PrimitiveBox& p : prims) box.extend(p.box);
  t.center = 0.5f * (box.lo + box.hi);
  // The seed's cube around the object space, a hair larger than the box so no box touches it.
  t.half = 0.5f * maxComponent(box.hi - box.lo) * (1 + 1e-5f);
  const int k =
      levels > 0 ? levels : static_cast<int>(std::ceil(std::log2(double(prims.size())) / 3));
  // A point-like or unbounded (past float's range) box is not cut at all.
  const int cut =
      t.half > 0 && std::isfinite(t.half) && isFinite(t.center) ? std::clamp(k, 0, kMaxLevels) : 0;
  t.prims = std::move(prims);
  std::vector<uint32_t> all(t.prims.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  t.nodes.resize(1);
  Builder(t, cut).build(0, t.center, t.half, std::move(all), 0, maxDepth);
  return t;
}

}  // namespace

Octree::Octree(const Scene& scene, int levels) : TwoLevelAccelerator(scene) {
  const auto start = std::chrono::steady_clock::now();
  trees_.resize(scene.groups.size());
  // Instanced groups first (they follow their parents): an instance's box is its group's box.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    std::vector<PrimitiveBox> prims =
        groupPrimitives(scene, uint32_t(g), [&](uint32_t child) { return trees_[child].box; });
    if (prims.empty()) continue;
    Tree& t = trees_[g] = buildTree(std::move(prims), levels, stats_.maxDepth);
    stats_.primitives += t.prims.size();
    stats_.references += t.refs.size();
    stats_.nodes += t.nodes.size();
    for (const Node& n : t.nodes) stats_.leaves += n.firstChild == kInvalidId;
    stats_.bytes += t.nodes.size() * sizeof(Node) + t.refs.size() * sizeof(uint32_t) +
                    t.prims.size() * sizeof(PrimitiveBox);
  }
  stats_.buildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <bool AnyHit, class Counter>
bool Octree::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                      Counter count) const {
  const Tree& t = trees_[groupId];
  if (t.prims.empty()) return false;
  const RaySlabs slabs(ray);
  const Vec3f h{t.half, t.half, t.half};
  float tEnter = ray.tMin, tLeave = std::min(ray.tMax, hit.t);
  if (!slabTest({t.center - h, t.center + h}, ray, slabs, tEnter, tLeave)) return false;

  // Cells still to visit, nearest on top: a cell's octants are pushed farthest first.
  struct Cell {
    uint32_t node;
    Vec3f center;
    float half, t0, t1;
  };
  Cell stack[4 * (kMaxLevels + 1)];
  int top = 0;
  stack[top++] = {0, t.center, t.half, tEnter, tLeave};
  bool found = false;
  while (top > 0) {
    const Cell c = stack[--top];
    // Every cell left starts beyond the closest hit: none holds a closer one.
    if (found && hit.t < c.t0) break;
    const Node& n = t.nodes[c.node];
    count.step();
    if (n.firstChild == kInvalidId) {
      for (uint32_t k = n.refStart; k < n.refStart + n.refCount; ++k) {
        const PrimitiveBox& p = t.prims[t.refs[k]];
        count.test();
        if (intersectPrimitive(scene_, groupId, p.geom, p.prim, ray, instId, hit,
                               intoInstance(count))) {
          if constexpr (AnyHit) return true;
          found = true;
        }
      }
      continue;
    }
    // Where the ray crosses the three mid-planes, and the octant it is in at c.t0.
    std::array<float, 3> tMid;
    int octant = 0;
    for (int a = 0; a < 3; ++a) {
      if (ray.d[a] == 0) {
        tMid[size_t(a)] = kInfinity;
        octant |= (ray.o[a] >= c.center[a]) << a;
        continue;
      }
      tMid[size_t(a)] = (c.center[a] - ray.o[a]) * slabs.inv[a];
      const bool upper = ray.d[a] > 0 ? c.t0 >= tMid[size_t(a)] : c.t0 < tMid[size_t(a)];
      octant |= upper << a;
    }
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return tMid[size_t(a)] < tMid[size_t(b)]; });
    // The octants along the ray, each crossing of a mid-plane flipping that axis's bit.
    Cell along[4];
    int octants = 0;
    float from = c.t0;
    for (int a : order) {
      const float cross = tMid[size_t(a)];
      if (!(cross > c.t0 && cross < c.t1)) continue;
      along[octants++] = {uint32_t(octant), {}, 0, from, cross};
      from = cross;
      octant ^= 1 << a;
    }
    along[octants++] = {uint32_t(octant), {}, 0, from, c.t1};
    const float quarter = c.half / 2;
    for (int i = octants; i-- > 0;) {
      const uint32_t k = along[i].node;
      const uint32_t child = n.firstChild + k;
      const Node& cn = t.nodes[child];
      if (cn.firstChild == kInvalidId && cn.refCount == 0) continue;  // an empty cell
      const Vec3f offset{(k & 1) ? quarter : -quarter, (k & 2) ? quarter : -quarter,
                         (k & 4) ? quarter : -quarter};
      stack[top++] = {child, c.center + offset, quarter, along[i].t0, along[i].t1};
    }
  }
  return found;
}

}  // namespace glint
