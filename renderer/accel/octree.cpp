#include "accel/octree.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "accel/surface_cell_overlap.h"
#include "core/seconds_since.h"

namespace glint {

namespace {

// A cell stops being cut when it holds this few primitives: eight more cells would cost more
// steps than the tests they save.
constexpr size_t kLeafPrimitives = 2;
// 2^10 cells per axis at the finest level at most, as the uniform grid's resolution.
constexpr int kMaxLevels = 10;

// The octant of a cell centred at `c` that holds p (a point on a mid-plane goes up).
int octantOf(const Vec3f& p, const Vec3f& c) {
  return int(p.x >= c.x) | int(p.y >= c.y) << 1 | int(p.z >= c.z) << 2;
}

// Octant k of the cell `cell` centred at `c`, and the octant's own centre (the one arithmetic
// that the build and both walks share, so that they agree on every cell to the last bit).
Bounds3f octantBox(const Bounds3f& cell, const Vec3f& c, int k) {
  Bounds3f b = cell;
  for (int a = 0; a < 3; ++a) ((k >> a & 1) ? b.lo[a] : b.hi[a]) = c[a];
  return b;
}
Vec3f octantCenter(const Vec3f& c, float half, int k) {
  const float quarter = half / 2;
  return c + Vec3f{(k & 1) ? quarter : -quarter, (k & 2) ? quarter : -quarter,
                   (k & 4) ? quarter : -quarter};
}

class OctreeBuilder {
 public:
  OctreeBuilder(const Scene& scene, uint32_t groupId, Octree::Tree& tree, int levels,
                SubdivisionStats& stats)
      : scene_(scene),
        groupId_(groupId),
        t_(tree),
        levels_(levels),
        stats_(stats),
        budget_(referenceBudget(tree.prims.size())),
        references_(double(tree.prims.size())) {}

  // `inside`: the cell lies inside some primitive's solid.
  void build(uint32_t node, const Vec3f& center, float half, const Bounds3f& cell,
             std::vector<uint32_t> list, int depth, bool inside) {
    stats_.maxDepth = std::max(stats_.maxDepth, size_t(depth));
    if (depth < levels_ && list.size() > kLeafPrimitives) {
      // The octants each primitive's surface meets (seed 002's "partial" cells).
      std::array<std::vector<uint32_t>, 8> octants;
      std::array<bool, 8> insideOctant;
      insideOctant.fill(inside);
      size_t listed = 0;
      for (int k = 0; k < 8; ++k) {
        const Bounds3f box = paddedCell(octantBox(cell, center, k));
        for (uint32_t i : list) {
          const CellContact contact = paddedSurfaceContact(scene_, groupId_, t_.prims[i], box);
          if (contact == CellContact::Surface) octants[size_t(k)].push_back(i), ++listed;
          if (contact == CellContact::Inside) insideOctant[size_t(k)] = true;
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
        for (int k = 0; k < 8; ++k)
          build(first + uint32_t(k), octantCenter(center, half, k), half / 2,
                octantBox(cell, center, k), std::move(octants[size_t(k)]), depth + 1,
                insideOctant[size_t(k)]);
        return;
      }
    }
    if (list.empty()) ++(inside ? stats_.fullLeaves : stats_.emptyLeaves);
    t_.nodes[node].refStart = static_cast<uint32_t>(t_.refs.size());
    t_.nodes[node].refCount = static_cast<uint32_t>(list.size());
    t_.refs.insert(t_.refs.end(), list.begin(), list.end());
  }

 private:
  const Scene& scene_;
  uint32_t groupId_;
  Octree::Tree& t_;
  int levels_;
  SubdivisionStats& stats_;
  double budget_;
  double references_;  // in all lists made so far (the root's n to begin with)
};

Octree::Tree buildTree(const Scene& scene, uint32_t groupId, std::vector<PrimitiveBox> prims,
                       int levels, SubdivisionStats& stats) {
  Octree::Tree t;
  Bounds3f& box = t.box;
  for (const PrimitiveBox& p : prims) box.extend(p.box);
  t.center = 0.5f * (box.lo + box.hi);
  // The seed's cube around the object space, a hair larger than the box so no box touches it.
  t.half = 0.5f * maxComponent(box.hi - box.lo) * (1 + 1e-5f);
  const Vec3f h{t.half, t.half, t.half};
  t.cube = {t.center - h, t.center + h};
  const int k =
      levels > 0 ? levels : static_cast<int>(std::ceil(std::log2(double(prims.size())) / 3));
  // A point-like or unbounded (past float's range) box is not cut at all.
  int cut = t.half > 0 && std::isfinite(t.half) && isFinite(t.center) && isFinite(t.cube.lo) &&
                    isFinite(t.cube.hi)
                ? std::clamp(k, 0, kMaxLevels)
                : 0;
  // Nor cut finer than 2⁻²⁰ of the cube's largest coordinate (8 float steps): the walks step
  // b/2 past a face, which must leave the cell, and centres must stay distinct.
  const float reach = std::max(maxComponent(abs(t.cube.lo)), maxComponent(abs(t.cube.hi)));
  while (cut > 0 && std::ldexp(2 * t.half, -cut) < 0x1p-20f * reach) --cut;
  t.step = std::ldexp(t.half, -cut);
  t.prims = std::move(prims);
  std::vector<uint32_t> all(t.prims.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  t.nodes.resize(1);
  OctreeBuilder(scene, groupId, t, cut, stats)
      .build(0, t.center, t.half, t.cube, std::move(all), 0, false);
  return t;
}

}  // namespace

Octree::Octree(const Scene& scene, int levels, Walk walk)
    : TwoLevelAccelerator(scene), walk_(walk) {
  const auto start = std::chrono::steady_clock::now();
  trees_.resize(scene.groups.size());
  // Instanced groups first (they follow their parents): an instance's box is its group's box.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    std::vector<PrimitiveBox> prims =
        groupPrimitives(scene, uint32_t(g), [&](uint32_t child) { return trees_[child].box; });
    if (prims.empty()) continue;
    Tree& t = trees_[g] = buildTree(scene, uint32_t(g), std::move(prims), levels, stats_);
    stats_.primitives += t.prims.size();
    stats_.references += t.refs.size();
    stats_.nodes += t.nodes.size();
    for (const Node& n : t.nodes) stats_.leaves += n.firstChild == kInvalidId;
    stats_.bytes += t.nodes.size() * sizeof(Node) + t.refs.size() * sizeof(uint32_t) +
                    t.prims.size() * sizeof(PrimitiveBox);
  }
  stats_.buildSeconds = secondsSince(start);
}

template <bool AnyHit, class Counter>
bool Octree::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                      Counter count) const {
  return walk_ == Walk::MidPlane ? walkMidPlanes<AnyHit>(groupId, ray, instId, hit, count)
                                 : generateAndTest<AnyHit>(groupId, ray, instId, hit, count);
}

template <bool AnyHit, class Counter>
bool Octree::testLeaf(uint32_t groupId, uint32_t node, const Ray& ray, uint32_t instId, Hit& hit,
                      Counter count) const {
  const Tree& t = trees_[groupId];
  const Node& n = t.nodes[node];
  return testList<AnyHit>(groupId, t.prims.data(), t.refs.data() + n.refStart, n.refCount, ray,
                          instId, hit, count);
}

template <bool AnyHit, class Counter>
bool Octree::generateAndTest(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                             Counter count) const {
  const Tree& t = trees_[groupId];
  if (t.prims.empty()) return false;
  const RaySlabs slabs(ray);
  float tEnter = ray.tMin, tLeave = std::min(ray.tMax, hit.t);
  if (!slabTest(t.cube, ray, slabs, tEnter, tLeave)) return false;
  // The first point: the origin, or where a ray from outside enters the cube. A cell holds
  // [lo, hi) along each axis (Classify sends a point on a mid-plane up), so a coordinate is
  // kept below the cube's upper faces and above its lower ones.
  const auto below = [](float x) { return std::nextafter(x, -kInfinity); };
  Vec3f q = ray.o + tEnter * ray.d;
  for (int a = 0; a < 3; ++a) q[a] = std::clamp(q[a], t.cube.lo[a], below(t.cube.hi[a]));
  bool found = false;
  while (true) {
    // Classify(q): from the root down to the leaf holding q, keeping the leaf's faces.
    uint32_t node = 0;
    Vec3f c = t.center;
    float half = t.half;
    Bounds3f cell = t.cube;
    count.step();
    while (t.nodes[node].firstChild != kInvalidId) {
      const int k = octantOf(q, c);
      cell = octantBox(cell, c, k);
      c = octantCenter(c, half, k);
      half /= 2;
      node = t.nodes[node].firstChild + uint32_t(k);
      count.step();
    }
    if (testLeaf<AnyHit>(groupId, node, ray, instId, hit, count)) {
      if constexpr (AnyHit) return true;
      found = true;
    }
    // Where the ray leaves the leaf: the nearest of the faces it heads for.
    Vec3f tFace{kInfinity, kInfinity, kInfinity};
    for (int a = 0; a < 3; ++a)
      if (ray.d[a] != 0)
        tFace[a] = ((ray.d[a] > 0 ? cell.hi[a] : cell.lo[a]) - ray.o[a]) * slabs.inv[a];
    const float tExit = std::min({tFace.x, tFace.y, tFace.z});
    // The ray ends in this leaf, or its closest hit lies here: no later leaf holds a closer.
    if (!(tExit < std::min(ray.tMax, hit.t))) break;
    // q = e + (b/2)·(the axes of the faces the ray leaves by), eq. 9.18: past each of those
    // faces by half the smallest cell (in the next leaf, whatever its size), and at least one
    // float step (so q leaves this leaf); along the other axes the ray's own coordinate at e,
    // held inside this leaf, whose exit float rounding might otherwise skip for a neighbour.
    bool leaves = false;
    for (int a = 0; a < 3; ++a) {
      if (tFace[a] == tExit) {
        if (ray.d[a] > 0) {
          leaves |= cell.hi[a] == t.cube.hi[a];
          q[a] = std::max(cell.hi[a] + t.step, cell.hi[a]);
        } else {
          leaves |= cell.lo[a] == t.cube.lo[a];
          q[a] = std::min(cell.lo[a] - t.step, below(cell.lo[a]));
        }
      } else {
        q[a] = std::clamp(ray.o[a] + tExit * ray.d[a], cell.lo[a], below(cell.hi[a]));
      }
    }
    if (leaves) break;  // out of the root cube
  }
  return found;
}

template <bool AnyHit, class Counter>
bool Octree::walkMidPlanes(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                           Counter count) const {
  const Tree& t = trees_[groupId];
  if (t.prims.empty()) return false;
  const RaySlabs slabs(ray);
  float tEnter = ray.tMin, tLeave = std::min(ray.tMax, hit.t);
  if (!slabTest(t.cube, ray, slabs, tEnter, tLeave)) return false;

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
      if (testLeaf<AnyHit>(groupId, c.node, ray, instId, hit, count)) {
        if constexpr (AnyHit) return true;
        found = true;
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
    for (int i = octants; i-- > 0;) {
      const uint32_t k = along[i].node;
      const uint32_t child = n.firstChild + k;
      const Node& cn = t.nodes[child];
      if (cn.firstChild == kInvalidId && cn.refCount == 0) continue;  // empty or full
      stack[top++] = {child, octantCenter(c.center, c.half, int(k)), c.half / 2, along[i].t0,
                      along[i].t1};
    }
  }
  return found;
}

}  // namespace glint
