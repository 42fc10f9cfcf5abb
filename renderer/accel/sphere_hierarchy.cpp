#include "accel/sphere_hierarchy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "accel/sah_bins.h"
#include "core/check.h"
#include "core/seconds_since.h"
#include "scene/scene.h"

namespace glint {

namespace {

// The float just above a double: a radius rounded up, so the float sphere still encloses.
float roundedUp(double x) {
  const float f = static_cast<float>(x);
  return std::nextafter(f, kInfinity);
}

double distance(const Vec3f& a, const Vec3f& b) {
  const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Halving before adding is exact and cannot overflow, unlike lo + hi near ±3.4e38.
Vec3f boxCenter(const Bounds3f& b) { return 0.5f * b.lo + 0.5f * b.hi; }

// The sphere centred at `c` enclosing every sphere of `inner` (the same double expression that
// checkInvariants evaluates, then rounded up).
Sphere enclosingAt(const Vec3f& c, const Sphere* inner, size_t n) {
  double r = 0;
  for (size_t i = 0; i < n; ++i) r = std::max(r, distance(c, inner[i].center) + inner[i].radius);
  return {c, roundedUp(r)};
}

Sphere enclosingBox(const Bounds3f& b) {
  const Vec3f c = boxCenter(b);
  double r = 0;
  for (int k = 0; k < 8; ++k) r = std::max(r, distance(c, b.corner(k)));
  return {c, roundedUp(r)};
}

// The smallest sphere around spheres a and b (centre on the line through their centres).
Sphere mergedCenter(const Sphere& a, const Sphere& b) {
  const double d = distance(a.center, b.center);
  if (d + b.radius <= a.radius) return a;
  if (d + a.radius <= b.radius) return b;
  const double r = 0.5 * (d + a.radius + b.radius);
  const double s = (r - a.radius) / d;  // from a's centre towards b's
  const auto along = [&](float p, float q) { return float(double(p) + s * (double(q) - p)); };
  return {
      {along(a.center.x, b.center.x), along(a.center.y, b.center.y), along(a.center.z, b.center.z)},
      float(r)};
}

bool encloses(const Sphere& outer, const Sphere& inner) {
  return distance(outer.center, inner.center) + inner.radius <= outer.radius;
}

// Where `ray` runs inside sphere `s` before `tFar`: false when it surely does not, else the
// entry distance (at least ray.tMin) in `entry`. Ray Tracing Gems ch. 7 (Haines et al. 2019):
// the discriminant from the perpendicular vector l = f − (f·d/d·d)d, which keeps its precision
// when the ray passes far from the centre, and the roots as c/q and q/a, which do not cancel.
// Conservative: the radius is grown, and the distances widened, by 2⁻¹⁹ (32 float steps) of the
// sizes they are computed from (|f|₁ + r), more than the few steps those float expressions can
// lose, so rounding never drops a sphere that the ray meets; a NaN anywhere (overflow near
// ±3.4e38) keeps the sphere too.
// a = d·d and its reciprocal, the same for every sphere of a ray.
struct DirectionTerms {
  float a, invA;
  explicit DirectionTerms(const Vec3f& d) : a(dot(d, d)), invA(1 / a) {}
};

bool entersSphere(const Sphere& s, const Ray& ray, const DirectionTerms& k, float tFar,
                  float& entry) {
  constexpr float kPad = 0x1p-19f;
  const Vec3f f = ray.o - s.center;
  const float size = std::abs(f.x) + std::abs(f.y) + std::abs(f.z) + s.radius;
  const float r = s.radius + kPad * size;
  const float b = -dot(f, ray.d);
  const Vec3f l = f + (b * k.invA) * ray.d;
  const float r2 = r * r;
  const float disc = k.a * (r2 - dot(l, l));
  if (disc < 0) return false;
  const float q = b + std::copysign(std::sqrt(disc), b);
  float t0 = -kInfinity, t1 = kInfinity;
  if (q != 0) {
    const float c = dot(f, f) - r2;
    t0 = c / q;
    t1 = q * k.invA;
    if (t0 > t1) std::swap(t0, t1);
    const float widen = kPad * (std::abs(t0) + std::abs(t1));
    t0 -= widen;
    t1 += widen;
  }
  if (t1 < ray.tMin || t0 > tFar) return false;
  entry = std::max(ray.tMin, t0);  // a NaN t0 leaves tMin
  return true;
}

struct BuildPrim {
  Bounds3f box;
  Vec3f center;
  SphereHierarchy::Slot slot;
};

class HierarchyBuilder {
 public:
  HierarchyBuilder(std::vector<BuildPrim>& prims, SphereHierarchy::Tree& tree,
                   SubdivisionStats& stats)
      : prims_(prims), tree_(tree), stats_(stats) {}

  // Appends the subtree of prims [begin, end) in pre-order and returns its root's index.
  uint32_t build(size_t begin, size_t end, size_t depth) {
    const auto index = static_cast<uint32_t>(tree_.nodes.size());
    tree_.nodes.emplace_back();
    stats_.maxDepth = std::max(stats_.maxDepth, depth);
    Bounds3f box, centers;
    for (size_t i = begin; i < end; ++i) {
      box.extend(prims_[i].box);
      centers.extend(prims_[i].center);
    }
    size_t mid = 0;
    if (!split(begin, end, centers, box, depth, mid)) {
      tree_.nodes[index].first = static_cast<uint32_t>(tree_.slots.size());
      tree_.nodes[index].count = static_cast<uint32_t>(end - begin);
      std::vector<Sphere> inner;
      for (size_t i = begin; i < end; ++i) {
        tree_.slots.push_back(prims_[i].slot);
        inner.push_back(prims_[i].slot.bound);
      }
      // One primitive: its own sphere; more: the box-centred sphere around theirs.
      tree_.nodes[index].bound =
          inner.size() == 1 ? inner[0] : enclosingAt(boxCenter(box), inner.data(), inner.size());
      ++stats_.leaves;
      return index;
    }
    build(begin, mid, depth + 1);
    const uint32_t second = build(mid, end, depth + 1);
    tree_.nodes[index].first = second;
    const Sphere children[2] = {tree_.nodes[index + 1].bound, tree_.nodes[second].bound};
    const Sphere merged = mergedCenter(children[0], children[1]);
    // The merged centre is rounded to float: the radius is measured again from it.
    const Sphere a = enclosingAt(merged.center, children, 2);
    const Sphere b = enclosingAt(boxCenter(box), children, 2);
    tree_.nodes[index].bound = a.radius <= b.radius ? a : b;
    return index;
  }

 private:
  // Chooses where to cut [begin, end); false makes a leaf.
  bool split(size_t begin, size_t end, const Bounds3f& centers, const Bounds3f& box, size_t depth,
             size_t& mid) {
    const size_t count = end - begin;
    if (count <= 1) return false;
    const Vec3f extent = centers.diagonal();
    const int axis =
        extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
    const bool spread = extent[axis] > 0 && std::isfinite(extent[axis]);
    if (spread && depth < SphereHierarchy::kMedianBelowDepth) {
      int leafOrBin = 0;
      if (sahBin(begin, end, centers, box, axis, leafOrBin)) {
        const CentroidBins<kBins> binOf(centers.lo[axis], centers.hi[axis]);
        const auto it =
            std::partition(prims_.begin() + long(begin), prims_.begin() + long(end),
                           [&](const BuildPrim& p) { return binOf(p.center[axis]) <= leafOrBin; });
        mid = static_cast<size_t>(it - prims_.begin());
        if (mid != begin && mid != end) return true;
      } else if (leafOrBin < 0) {
        return false;  // a leaf costs less than any split
      }
    }
    if (count <= size_t(SphereHierarchy::kMaxLeafSize)) return false;
    // The object median: coincident centroids, a bin split that left a side empty, or depth.
    mid = begin + count / 2;
    std::nth_element(
        prims_.begin() + long(begin), prims_.begin() + long(mid), prims_.begin() + long(end),
        [&](const BuildPrim& p, const BuildPrim& q) { return p.center[axis] < q.center[axis]; });
    return true;
  }

  static constexpr int kBins = SphereHierarchy::kBins;

  // The binned SAH along `axis`: true with the last bin of the left side in `bin`; false with
  // bin = −1 when a leaf of ≤ kMaxLeafSize costs less, or bin = 0 when no bin separates anything.
  bool sahBin(size_t begin, size_t end, const Bounds3f& centers, const Bounds3f& box, int axis,
              int& bin) {
    const CentroidBins<kBins> binOf(centers.lo[axis], centers.hi[axis]);
    bin = 0;
    if (!binOf.usable()) return false;
    Bounds3f bins[kBins];
    size_t counts[kBins] = {};
    for (size_t i = begin; i < end; ++i) {
      const int b = binOf(prims_[i].center[axis]);
      bins[b].extend(prims_[i].box);
      ++counts[b];
    }
    float best = 0;
    const int bestBin = cheapestCut<kBins>(bins, counts, best);
    if (bestBin < 0) return false;
    const size_t count = end - begin;
    if (count <= size_t(SphereHierarchy::kMaxLeafSize) &&
        best + surfaceArea(box) >= float(count) * surfaceArea(box)) {
      bin = -1;
      return false;
    }
    bin = bestBin;
    return true;
  }

  std::vector<BuildPrim>& prims_;
  SphereHierarchy::Tree& tree_;
  SubdivisionStats& stats_;
};

// Primitive `p`'s own sphere (see the header for the rule).
SphereHierarchy::Slot slotOf(const Scene& scene, uint32_t groupId, const PrimitiveBox& p) {
  SphereHierarchy::Slot slot{enclosingBox(p.box), p.geom, p.prim, false};
  const Geometry& g = scene.groups[groupId].geometries[p.geom];
  if (g.kind == GeomKind::Sphere && scene.sphereCenterKeys[g.index].empty()) {
    slot.bound = scene.spheres[g.index];
    slot.exact = true;
  } else if (g.kind == GeomKind::Mesh && !scene.meshes[g.index].deforming()) {
    const TriangleMesh& m = scene.meshes[g.index];
    const Vec3f v[3] = {m.vertex(p.prim, 0), m.vertex(p.prim, 1), m.vertex(p.prim, 2)};
    const Vec3f mean = v[0] / 3.0f + v[1] / 3.0f + v[2] / 3.0f;
    const Sphere corners[3] = {{v[0], 0}, {v[1], 0}, {v[2], 0}};
    const Sphere around = enclosingAt(mean, corners, 3);
    if (around.radius < slot.bound.radius) slot.bound = around;
  }
  return slot;
}

}  // namespace

SphereHierarchy::SphereHierarchy(const Scene& scene) : TwoLevelAccelerator(scene) {
  const auto start = std::chrono::steady_clock::now();
  trees_.resize(scene.groups.size());
  // Instanced groups first: an instance's box is its group's box, transformed.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    Tree& tree = trees_[g];
    std::vector<BuildPrim> prims;
    for (const PrimitiveBox& p :
         groupPrimitives(scene, uint32_t(g), [&](uint32_t child) { return trees_[child].box; })) {
      tree.box.extend(p.box);
      prims.push_back({p.box, boxCenter(p.box), slotOf(scene, uint32_t(g), p)});
    }
    if (prims.empty()) continue;
    HierarchyBuilder(prims, tree, stats_).build(0, prims.size(), 0);
    stats_.nodes += tree.nodes.size();
    stats_.primitives += tree.slots.size();
    stats_.bytes += tree.nodes.size() * sizeof(Node) + tree.slots.size() * sizeof(Slot);
  }
  stats_.references = stats_.primitives;
  // The traversal stack holds at most one entry per level.
  GLINT_CHECK(stats_.maxDepth < kMaxDepth);
  stats_.buildSeconds = secondsSince(start);
}

Sphere SphereHierarchy::rootSphere(uint32_t groupId) const {
  const Tree& t = trees_[groupId];
  return t.nodes.empty() ? Sphere{{0, 0, 0}, -1} : t.nodes[0].bound;
}

template <bool AnyHit, class Counter>
bool SphereHierarchy::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                               Counter count) const {
  const Tree& tree = trees_[groupId];
  if (tree.nodes.empty()) return false;
  const auto far = [&] { return std::min(ray.tMax, hit.t); };
  struct Entry {
    uint32_t node;
    float t;
  };
  Entry stack[kMaxDepth];
  int sp = 0;
  uint32_t index = 0;
  float entry = 0;
  count.step();
  const DirectionTerms terms(ray.d);
  if (!entersSphere(tree.nodes[0].bound, ray, terms, far(), entry)) return false;
  bool found = false;
  while (true) {
    const Node& node = tree.nodes[index];
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) {
        const Slot& s = tree.slots[i];
        if (!s.exact) {
          count.step();
          float t;
          if (!entersSphere(s.bound, ray, terms, far(), t)) continue;
        }
        count.test();
        if (intersectPrimitive(scene_, groupId, s.geom, s.prim, ray, instId, hit,
                               intoInstance(count))) {
          if constexpr (AnyHit) return true;
          found = true;
        }
      }
    } else {
      uint32_t near = index + 1, other = node.first;
      float tNear = 0, tOther = 0;
      count.step();
      count.step();
      const bool hitNear = entersSphere(tree.nodes[near].bound, ray, terms, far(), tNear);
      const bool hitOther = entersSphere(tree.nodes[other].bound, ray, terms, far(), tOther);
      if (hitNear && hitOther) {
        if (tOther < tNear) {
          std::swap(near, other);
          std::swap(tNear, tOther);
        }
        stack[sp++] = {other, tOther};
        index = near;
        continue;
      }
      if (hitNear || hitOther) {
        index = hitNear ? near : other;
        continue;
      }
    }
    // The next pending sphere that the ray enters before the closest hit so far.
    do {
      if (sp == 0) return found;
      --sp;
    } while (stack[sp].t > far());
    index = stack[sp].node;
  }
}

std::string SphereHierarchy::checkInvariants() const {
  for (size_t g = 0; g < trees_.size(); ++g) {
    const Tree& t = trees_[g];
    // The primitives' boxes again, by (geometry, primitive), to check their spheres against.
    std::map<std::pair<uint32_t, uint32_t>, Bounds3f> boxes;
    for (const PrimitiveBox& p :
         groupPrimitives(scene_, uint32_t(g), [&](uint32_t child) { return trees_[child].box; }))
      boxes[{p.geom, p.prim}] = p.box;
    if (boxes.size() != t.slots.size())
      return "group " + std::to_string(g) + ": " + std::to_string(t.slots.size()) +
             " primitives in leaves, expected " + std::to_string(boxes.size());
    std::vector<int> seen(t.slots.size(), 0);
    for (size_t i = 0; i < t.nodes.size(); ++i) {
      const Node& n = t.nodes[i];
      const std::string where = "group " + std::to_string(g) + " node " + std::to_string(i);
      if (n.count == 0) {
        if (!encloses(n.bound, t.nodes[i + 1].bound) || !encloses(n.bound, t.nodes[n.first].bound))
          return where + ": a child's sphere is not inside its parent's";
        continue;
      }
      for (uint32_t p = n.first; p < n.first + n.count; ++p) {
        ++seen[p];
        if (!encloses(n.bound, t.slots[p].bound))
          return where + ": a primitive's sphere is not inside its leaf's";
      }
    }
    for (size_t p = 0; p < t.slots.size(); ++p) {
      const std::string where = "group " + std::to_string(g) + " slot " + std::to_string(p);
      if (seen[p] != 1) return where + " is in " + std::to_string(seen[p]) + " leaves";
      const Slot& s = t.slots[p];
      const Geometry& geom = scene_.groups[g].geometries[s.geom];
      if (s.exact) continue;
      if (geom.kind == GeomKind::Mesh && !scene_.meshes[geom.index].deforming()) {
        for (int c = 0; c < 3; ++c)
          if (!encloses(s.bound, {scene_.meshes[geom.index].vertex(s.prim, c), 0}))
            return where + ": a corner of the triangle is outside its sphere";
      } else {
        const auto box = boxes.find({s.geom, s.prim});
        if (box == boxes.end()) return where + " names no primitive of the group";
        for (int c = 0; c < 8; ++c)
          if (!encloses(s.bound, {box->second.corner(c), 0}))
            return where + ": a corner of the primitive's box is outside its sphere";
      }
    }
  }
  return {};
}

}  // namespace glint
