#include "accel/reference_bvh.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>

#include "accel/primitives.h"
#include "accel/sah_bins.h"
#include "core/check.h"
#include "core/seconds_since.h"
#include "scene/scene.h"

namespace glint {

namespace {

// Halving before adding is exact and cannot overflow, unlike lo + hi near ±3.4e38.
Vec3f centroid(const Bounds3f& b) { return 0.5f * b.lo + 0.5f * b.hi; }

bool contains(const Bounds3f& outer, const Bounds3f& inner) {
  return inner.lo.x >= outer.lo.x && inner.lo.y >= outer.lo.y && inner.lo.z >= outer.lo.z &&
         inner.hi.x <= outer.hi.x && inner.hi.y <= outer.hi.y && inner.hi.z <= outer.hi.z;
}

struct BuildPrim {
  Bounds3f box;
  Vec3f center;
  ReferenceBvh::PrimRef ref;
};

struct BuildNode {
  Bounds3f box;
  std::unique_ptr<BuildNode> child[2];
  int axis = 0;
  size_t first = 0, count = 0;  // leaf range in the prims array
};

class BvhBuilder {
 public:
  BvhBuilder(std::vector<BuildPrim>& prims, BvhSplit split) : prims_(prims), split_(split) {}

  std::unique_ptr<BuildNode> build(size_t begin, size_t end) {
    auto node = std::make_unique<BuildNode>();
    Bounds3f centers;
    for (size_t i = begin; i < end; ++i) {
      node->box.extend(prims_[i].box);
      centers.extend(prims_[i].center);
    }
    const size_t count = end - begin;
    size_t mid = begin;
    int axis = 0;
    if (count <= 1 || !chooseSplit(begin, end, centers, node->box, mid, axis)) {
      node->first = begin;
      node->count = count;
      return node;
    }
    node->axis = axis;
    // Build big subtrees in parallel; the split point is fixed, so the tree is the same.
    if (count > 4096) {
      tbb::parallel_invoke([&] { node->child[0] = build(begin, mid); },
                           [&] { node->child[1] = build(mid, end); });
    } else {
      node->child[0] = build(begin, mid);
      node->child[1] = build(mid, end);
    }
    return node;
  }

 private:
  // Chooses a split; false means "make a leaf". Leaves hold at most kMaxLeafSize primitives.
  bool chooseSplit(size_t begin, size_t end, const Bounds3f& centers, const Bounds3f& box,
                   size_t& mid, int& axis) {
    const size_t count = end - begin;
    const Vec3f extent = centers.diagonal();
    axis = extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
    if (!(extent[axis] > 0)) {
      // All centroids coincide: no plane separates them; split the list in half if too big.
      if (count <= ReferenceBvh::kMaxLeafSize) return false;
      mid = begin + count / 2;
      return true;
    }
    if (split_ == BvhSplit::Sah && sahSplit(begin, end, centers, box, mid, axis)) return true;
    if (split_ == BvhSplit::Sah && count <= ReferenceBvh::kMaxLeafSize) return false;
    if (split_ == BvhSplit::Midpoint) {
      const float plane = 0.5f * centers.lo[axis] + 0.5f * centers.hi[axis];
      auto it = std::partition(prims_.begin() + long(begin), prims_.begin() + long(end),
                               [&](const BuildPrim& p) { return p.center[axis] < plane; });
      mid = static_cast<size_t>(it - prims_.begin());
      if (mid != begin && mid != end) return count > 1;
    }
    if (count <= 1) return false;
    // Object median (also the fallback when a midpoint or SAH split leaves a side empty).
    mid = begin + count / 2;
    std::nth_element(
        prims_.begin() + long(begin), prims_.begin() + long(mid), prims_.begin() + long(end),
        [&](const BuildPrim& a, const BuildPrim& b) { return a.center[axis] < b.center[axis]; });
    return true;
  }

  // Binned SAH over all three axes (Wald 2007). Returns false when no split beats a leaf.
  bool sahSplit(size_t begin, size_t end, const Bounds3f& centers, const Bounds3f& box, size_t& mid,
                int& axis) {
    constexpr int B = ReferenceBvh::kBins;
    const size_t count = end - begin;
    float bestCost = kInfinity;
    int bestAxis = -1, bestBin = 0;
    for (int a = 0; a < 3; ++a) {
      const CentroidBins<B> binOf(centers.lo[a], centers.hi[a]);
      if (!binOf.usable()) continue;
      Bounds3f bins[B];
      size_t counts[B] = {};
      for (size_t i = begin; i < end; ++i) {
        const int b = binOf(prims_[i].center[a]);
        bins[b].extend(prims_[i].box);
        ++counts[b];
      }
      float cost = 0;
      const int bin = cheapestCut<B>(bins, counts, cost);
      if (bin >= 0 && cost < bestCost) {
        bestCost = cost;
        bestAxis = a;
        bestBin = bin;
      }
    }
    if (bestAxis < 0) return false;
    // Leaf cost N·A(box) against traversal 1·A(box) + children (intersection cost 1).
    const float leafCost = float(count) * surfaceArea(box);
    if (count <= ReferenceBvh::kMaxLeafSize && bestCost + surfaceArea(box) >= leafCost)
      return false;
    axis = bestAxis;
    const CentroidBins<B> binOf(centers.lo[axis], centers.hi[axis]);
    auto it = std::partition(prims_.begin() + long(begin), prims_.begin() + long(end),
                             [&](const BuildPrim& p) { return binOf(p.center[axis]) <= bestBin; });
    mid = static_cast<size_t>(it - prims_.begin());
    return mid != begin && mid != end;
  }

  std::vector<BuildPrim>& prims_;
  BvhSplit split_;
};

// Pre-order flattening: the first child follows its parent; `first` names the second child.
void flatten(const BuildNode& n, const std::vector<BuildPrim>& prims, ReferenceBvh::Tree& tree,
             BvhStats& stats, size_t depth, float rootArea) {
  const auto index = static_cast<uint32_t>(tree.nodes.size());
  tree.nodes.push_back({n.box, 0, 0, static_cast<uint16_t>(n.axis)});
  stats.maxDepth = std::max(stats.maxDepth, depth);
  const float rel = rootArea > 0 ? surfaceArea(n.box) / rootArea : 1;
  if (!n.child[0]) {
    tree.nodes[index].first = static_cast<uint32_t>(tree.prims.size());
    tree.nodes[index].count = static_cast<uint16_t>(n.count);
    for (size_t i = n.first; i < n.first + n.count; ++i) tree.prims.push_back(prims[i].ref);
    ++stats.leaves;
    stats.primitives += n.count;
    stats.sahCost += rel * double(n.count);
    return;
  }
  stats.sahCost += rel;
  flatten(*n.child[0], prims, tree, stats, depth + 1, rootArea);
  tree.nodes[index].first = static_cast<uint32_t>(tree.nodes.size());
  flatten(*n.child[1], prims, tree, stats, depth + 1, rootArea);
}

}  // namespace

std::string_view bvhSplitName(BvhSplit s) {
  switch (s) {
    case BvhSplit::Sah:
      return "sah";
    case BvhSplit::Median:
      return "median";
    case BvhSplit::Midpoint:
      return "midpoint";
  }
  return "?";
}

ReferenceBvh::ReferenceBvh(const Scene& scene, BvhSplit split) : TwoLevelAccelerator(scene) {
  const auto start = std::chrono::steady_clock::now();
  trees_.resize(scene.groups.size());
  // Instanced groups first: an instance's box is its group's root box, transformed.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    const auto& geoms = scene.groups[g].geometries;
    std::vector<BuildPrim> prims;
    for (const PrimitiveBox& p : groupPrimitives(scene, uint32_t(g), [&](uint32_t child) {
           return trees_[child].nodes.empty() ? Bounds3f{} : trees_[child].nodes[0].box;
         }))
      prims.push_back({p.box, centroid(p.box), {p.geom, p.prim}});
    if (prims.empty()) continue;
    BvhBuilder builder(prims, split);
    const auto root = builder.build(0, prims.size());
    flatten(*root, prims, trees_[g], stats_, 0, surfaceArea(root->box));
    Tree& tree = trees_[g];
    tree.corners.resize(tree.prims.size());
    tree.staticTriangle.assign(tree.prims.size(), 0);
    for (size_t i = 0; i < tree.prims.size(); ++i) {
      const Geometry& geom = geoms[tree.prims[i].geom];
      if (geom.kind != GeomKind::Mesh || scene.meshes[geom.index].deforming()) continue;
      const TriangleMesh& m = scene.meshes[geom.index];
      tree.corners[i] = {m.vertex(tree.prims[i].prim, 0), m.vertex(tree.prims[i].prim, 1),
                         m.vertex(tree.prims[i].prim, 2)};
      tree.staticTriangle[i] = 1;
    }
    stats_.nodes += trees_[g].nodes.size();
    stats_.bytes += tree.nodes.size() * sizeof(Node) +
                    tree.prims.size() * (sizeof(PrimRef) + sizeof(tree.corners[0]) + 1);
  }
  // The traversal stack holds at most one entry per level.
  GLINT_CHECK(stats_.maxDepth < kMaxDepth);
  stats_.buildSeconds = secondsSince(start);
}

template <class Counter>
bool ReferenceBvh::intersectPrim(uint32_t groupId, uint32_t slot, const Ray& ray, uint32_t instId,
                                 Hit& hit, Counter count) const {
  count.test();
  const Tree& tree = trees_[groupId];
  const PrimRef& p = tree.prims[slot];
  if (tree.staticTriangle[slot]) {
    Ray r = ray;
    r.tMax = std::min(ray.tMax, hit.t);
    float u = 0, v = 0;
    const auto& c = tree.corners[slot];
    const float t = intersectTriangle(c[0], c[1], c[2], r, u, v);
    if (!(t < r.tMax)) return false;
    // A triangle meets a ray once: a hit in a cut-out's hole leaves nothing behind it.
    if (scene_.cutAway(scene_.groups[groupId].geometries[p.geom], r, t, p.prim, u, v)) return false;
    hit = Hit{t, u, v, p.geom, p.prim, instId};
    return true;
  }
  return intersectPrimitive(scene_, groupId, p.geom, p.prim, ray, instId, hit, intoInstance(count));
}

template <bool AnyHit, class Counter>
bool ReferenceBvh::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                            Counter count) const {
  const Tree& tree = trees_[groupId];
  if (tree.nodes.empty()) return false;
  const RaySlabs slabs(ray);
  uint32_t stack[kMaxDepth];
  int sp = 0;
  uint32_t index = 0;
  bool found = false;
  while (true) {
    const Node& node = tree.nodes[index];
    count.step();
    float tNear = ray.tMin, tFar = std::min(ray.tMax, hit.t);
    if (slabTest(node.box, ray, slabs, tNear, tFar)) {
      if (node.count > 0) {
        for (uint32_t i = node.first; i < node.first + node.count; ++i)
          if (intersectPrim(groupId, i, ray, instId, hit, count)) {
            if constexpr (AnyHit) return true;
            found = true;
          }
      } else {
        // Near child first: the one on the side the ray comes from along the split axis.
        const uint32_t first = index + 1, second = node.first;
        const bool swap = slabs.negative[node.axis] != 0;
        stack[sp++] = swap ? first : second;
        index = swap ? second : first;
        continue;
      }
    }
    if (sp == 0) break;
    index = stack[--sp];
  }
  return found;
}

std::string ReferenceBvh::checkInvariants() const {
  for (size_t g = 0; g < trees_.size(); ++g) {
    const Tree& t = trees_[g];
    std::vector<int> seen(t.prims.size(), 0);
    for (size_t i = 0; i < t.nodes.size(); ++i) {
      const Node& n = t.nodes[i];
      const std::string where = "group " + std::to_string(g) + " node " + std::to_string(i);
      if (n.count == 0) {
        if (!contains(n.box, t.nodes[i + 1].box) || !contains(n.box, t.nodes[n.first].box))
          return where + ": a child box is not inside its parent";
        continue;
      }
      if (n.count > kMaxLeafSize * 4) return where + ": leaf too large";
      for (uint32_t p = n.first; p < n.first + n.count; ++p) ++seen[p];
    }
    for (size_t p = 0; p < seen.size(); ++p)
      if (seen[p] != 1)
        return "group " + std::to_string(g) + " primitive slot " + std::to_string(p) + " is in " +
               std::to_string(seen[p]) + " leaves";
    std::vector<std::pair<uint32_t, uint32_t>> refs;
    for (const PrimRef& r : t.prims) refs.push_back({r.geom, r.prim});
    std::sort(refs.begin(), refs.end());
    if (std::adjacent_find(refs.begin(), refs.end()) != refs.end())
      return "group " + std::to_string(g) + ": a primitive is in two leaves";
    // Every primitive of the group appears once among the slots.
    size_t expected = 0;
    for (const Geometry& geom : scene_.groups[g].geometries) {
      if (geom.kind == GeomKind::Mesh)
        expected += scene_.meshes[geom.index].triangleCount();
      else if (geom.kind != GeomKind::Plane)
        ++expected;
    }
    if (expected != t.prims.size())
      return "group " + std::to_string(g) + ": " + std::to_string(t.prims.size()) +
             " primitives in leaves, expected " + std::to_string(expected);
  }
  return {};
}

}  // namespace glint
