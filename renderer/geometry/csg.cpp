#include "geometry/csg.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "core/slab_test.h"

namespace glint {

namespace {

// Where the line crosses one triangle of a mesh operand, and which way.
struct MeshCrossing {
  CsgBoundary at;
  bool entering = false;
};

// Buffers for one level of the operand tree: its result so far, the next operand's intervals,
// and their combination.
struct LevelBuffers {
  std::vector<CsgSpan> operand, combined;
};

// Per thread, reused from ray to ray. A deque: a deeper level added while a shallower one's
// buffers are in use must not move them.
struct Scratch {
  std::deque<LevelBuffers> levels;
  std::vector<MeshCrossing> crossings;
  std::vector<CsgSpan> result;
  LevelBuffers& at(size_t depth) {
    while (levels.size() <= depth) levels.emplace_back();
    return levels[depth];
  }
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// Closes gaps and then drops slivers up to `thin` (in t): a seam between abutting operands of a
// union, or the touching faces of an intersection, are rounding, not surfaces.
void tidy(std::vector<CsgSpan>& spans, float thin) {
  size_t kept = 0;
  for (size_t i = 0; i < spans.size(); ++i) {
    if (kept > 0 && spans[i].in.t - spans[kept - 1].out.t <= thin) {
      spans[kept - 1].out = spans[i].out;
      continue;
    }
    spans[kept++] = spans[i];
  }
  spans.resize(kept);
  std::erase_if(spans, [&](const CsgSpan& s) { return !(s.out.t - s.in.t > thin); });
}

// Leaves of a mesh operand's hierarchy hold at most this many triangles; median splits keep
// the depth within log₂ of the count, far below the traversal stack's bound.
constexpr uint32_t kMeshLeafTriangles = 4;
constexpr int kMaxMeshDepth = 64;

// A hierarchy over triangles [first, first + count) of `s`, reordered in place: split at the
// median centroid along the widest axis of the centroids. Node boxes are padded by a relative
// 2^-20 (and 2^-20 of the coordinates' size), so that a crossing on a box face, which the slab
// test and the triangle test may round to different sides, is never culled.
uint32_t buildMeshNode(CsgSolid& s, uint32_t first, uint32_t count) {
  const auto index = static_cast<uint32_t>(s.meshNodes.size());
  s.meshNodes.emplace_back();
  Bounds3f box, centroids;
  for (uint32_t i = first; i < first + count; ++i) {
    for (const Vec3f& p : s.triangles[i]) box.extend(p);
    centroids.extend((s.triangles[i][0] + s.triangles[i][1] + s.triangles[i][2]) / 3.0f);
  }
  const Vec3f pad = 0x1p-20f * (box.diagonal() + max(abs(box.lo), abs(box.hi)));
  box = {box.lo - pad, box.hi + pad};
  const Vec3f spread = centroids.diagonal();
  const int axis =
      spread.x > spread.y ? (spread.x > spread.z ? 0 : 2) : (spread.y > spread.z ? 1 : 2);
  if (count <= kMeshLeafTriangles || !(spread[axis] > 0)) {
    s.meshNodes[index] = {box, first, count, 0};
    return index;
  }
  const auto begin = s.triangles.begin() + first;
  std::nth_element(begin, begin + count / 2, begin + count, [axis](const auto& a, const auto& b) {
    return a[0][axis] + a[1][axis] + a[2][axis] < b[0][axis] + b[1][axis] + b[2][axis];
  });
  buildMeshNode(s, first, count / 2);  // index + 1
  const uint32_t second = buildMeshNode(s, first + count / 2, count - count / 2);
  s.meshNodes[index] = {box, 0, 0, second};
  return index;
}

// Everything a ray's evaluation needs besides the node.
struct LineQuery {
  const CsgSolid& solid;
  const Ray& ray;
  RaySlabs slabs;
  float thin;  // CsgSolid::thinness in units of t
};

// A closed mesh's inside intervals from its crossings in order along the line. Entering adds
// one to the winding, leaving takes one away; the line is inside where the winding is positive.
// A ray through an edge or vertex meets every triangle there (the watertight test promises at
// least one): crossings the same way within `thin` of each other count once, and a silhouette's
// enter-and-leave at one point cancels.
void meshSpans(const LineQuery& q, const CsgLeaf& leaf, uint32_t leafIndex, float tNear, float tFar,
               std::vector<MeshCrossing>& crossings, std::vector<CsgSpan>& out) {
  Ray r = q.ray;
  r.tMin = tNear - q.thin;
  r.tMax = tFar + q.thin;
  crossings.clear();
  // Every triangle of every hierarchy node the line segment reaches.
  uint32_t stack[kMaxMeshDepth + 1];
  int top = 0;
  stack[top++] = leaf.hierarchy;
  while (top > 0) {
    const CsgMeshNode& node = q.solid.meshNodes[stack[--top]];
    float t0 = r.tMin, t1 = r.tMax;
    if (!slabTest(node.box, r, q.slabs, t0, t1)) continue;
    if (node.count == 0) {
      stack[top++] = node.second;
      stack[top++] = uint32_t(&node - q.solid.meshNodes.data()) + 1;
      continue;
    }
    for (uint32_t tri = node.first; tri < node.first + node.count; ++tri) {
      const auto& p = q.solid.triangles[tri];
      float u = 0, v = 0;
      const float t = intersectTriangle(p[0], p[1], p[2], r, u, v);
      if (!(t < r.tMax)) continue;
      const float facing = dot(q.ray.d, cross(p[1] - p[0], p[2] - p[0]));
      if (facing == 0) continue;
      crossings.push_back({{t, q.solid.surfaceId(leafIndex, tri), u, v}, facing < 0});
    }
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const MeshCrossing& a, const MeshCrossing& b) { return a.at.t < b.at.t; });
  int winding = 0;
  float lastIn = -kInfinity, lastOut = -kInfinity;
  CsgSpan open;
  for (const MeshCrossing& c : crossings) {
    float& last = c.entering ? lastIn : lastOut;
    if (c.at.t - last <= q.thin) continue;  // the same crossing, met by a neighbouring triangle
    last = c.at.t;
    const bool wasInside = winding > 0;
    winding += c.entering ? 1 : -1;
    if (!wasInside && winding > 0) open.in = c.at;
    if (wasInside && winding <= 0) {
      open.out = c.at;
      out.push_back(open);
    }
  }
  // An interval left open lost its exit to rounding: it is dropped, not run to infinity.
}

void leafSpans(const LineQuery& q, uint32_t leafIndex, float tNear, float tFar, Scratch& s,
               std::vector<CsgSpan>& out) {
  const CsgLeaf& leaf = q.solid.leaves[leafIndex];
  if (leaf.isSphere) {
    float t0, t1;
    if (sphereRoots(leaf.sphere, q.ray, t0, t1)) {
      const uint32_t id = q.solid.surfaceId(leafIndex, kInvalidId);
      out.push_back({{t0, id, 0, 0}, {t1, id, 0, 0}});
    }
  } else {
    meshSpans(q, leaf, leafIndex, tNear, tFar, s.crossings, out);
  }
  tidy(out, q.thin);
}

// The inside intervals of node `index` along the line, into `out`; `depth` picks the scratch
// buffers of this level.
void evaluate(const LineQuery& q, uint32_t index, size_t depth, Scratch& s,
              std::vector<CsgSpan>& out) {
  out.clear();
  const CsgNode& node = q.solid.nodes[index];
  float tNear = -kInfinity, tFar = kInfinity;
  if (!slabTest(node.box, q.ray, q.slabs, tNear, tFar)) return;  // nothing of it on the line
  if (node.leaf != kInvalidId) return leafSpans(q, node.leaf, tNear, tFar, s, out);
  evaluate(q, node.operands[0], depth + 1, s, out);
  LevelBuffers& level = s.at(depth);
  for (size_t i = 1; i < node.operands.size(); ++i) {
    // Nothing is left to intersect or subtract from.
    if (out.empty() && node.op != CsgOp::Union) return;
    evaluate(q, node.operands[i], depth + 1, s, level.operand);
    combineSpans(node.op, out, level.operand, q.thin, level.combined);
    std::swap(out, level.combined);
  }
}

const CsgBoundary& endOf(const std::vector<CsgSpan>& spans, size_t event) {
  const CsgSpan& span = spans[event / 2];
  return event % 2 == 0 ? span.in : span.out;
}

}  // namespace

void combineSpans(CsgOp op, const std::vector<CsgSpan>& a, const std::vector<CsgSpan>& b,
                  float thin, std::vector<CsgSpan>& out) {
  // One sweep over both lists' ends in order along the line, tracking whether the line is
  // inside a and inside b; the combined solid's surface is where op(inside a, inside b) changes.
  out.clear();
  const size_t endsA = 2 * a.size(), endsB = 2 * b.size();
  size_t i = 0, j = 0;
  bool inA = false, inB = false, inside = false;
  CsgSpan open;
  while (i < endsA || j < endsB) {
    const bool fromA = j == endsB || (i < endsA && endOf(a, i).t <= endOf(b, j).t);
    const CsgBoundary& end = fromA ? endOf(a, i) : endOf(b, j);
    if (fromA)
      inA = i++ % 2 == 0;
    else
      inB = j++ % 2 == 0;
    const bool now = op == CsgOp::Union          ? (inA || inB)
                     : op == CsgOp::Intersection ? (inA && inB)
                                                 : (inA && !inB);
    if (now == inside) continue;
    inside = now;
    if (now) {
      open.in = end;
    } else {
      open.out = end;
      out.push_back(open);
    }
  }
  tidy(out, thin);
}

void CsgSolid::buildMeshHierarchies() {
  meshNodes.clear();
  for (CsgLeaf& leaf : leaves)
    if (!leaf.isSphere)
      leaf.hierarchy = buildMeshNode(*this, leaf.firstTriangle, leaf.triangleCount);
}

CsgSurface CsgSolid::surface(uint32_t id) const {
  if (id < leaves.size()) return {id, kInvalidId};
  const uint32_t tri = id - static_cast<uint32_t>(leaves.size());
  // Mesh leaves hold consecutive triangles: the last leaf starting at or before it.
  uint32_t leaf = 0;
  for (uint32_t l = 0; l < leaves.size(); ++l)
    if (!leaves[l].isSphere && leaves[l].firstTriangle <= tri &&
        tri < leaves[l].firstTriangle + leaves[l].triangleCount)
      leaf = l;
  return {leaf, tri};
}

Vec3f CsgSolid::normal(const CsgSurface& s, const Vec3f& p) const {
  Vec3f n;
  if (s.triangle == kInvalidId) {
    n = p - leaves[s.leaf].sphere.center;
  } else {
    const auto& tri = triangles[s.triangle];
    n = cross(tri[1] - tri[0], tri[2] - tri[0]);
  }
  return leaves[s.leaf].flipped ? -n : n;
}

namespace {

// The solid's spans along the ray's line into s.result, with t measured from where the line
// enters the solid's box (the returned shift): the intervals are computed from there, so their
// rounding scales with the solid's size, not with the distance of the ray's origin, which the
// tolerance `thinness` knows nothing of (a ray reflected from a wall 50 units away onto a
// small die). Empty when the line misses the box.
float lineSpans(const CsgSolid& solid, const Ray& ray, Scratch& s) {
  s.result.clear();
  const RaySlabs slabs(ray);
  float tEnter = -kInfinity, tLeave = kInfinity;
  if (!slabTest(solid.box(), ray, slabs, tEnter, tLeave)) return 0;
  const float shift = std::isfinite(tEnter) ? tEnter : 0;
  Ray local = ray;
  local.o = ray.o + shift * ray.d;
  evaluate({solid, local, slabs, solid.thinness / length(ray.d)}, 0, 0, s, s.result);
  return shift;
}

}  // namespace

bool CsgSolid::intersect(const Ray& ray, CsgBoundary& hit) const {
  Scratch& s = scratch();
  const float shift = lineSpans(*this, ray, s);
  for (const CsgSpan& span : s.result)
    for (const CsgBoundary* end : {&span.in, &span.out}) {
      const float t = shift + end->t;
      if (!(t < ray.tMax)) return false;
      if (t > ray.tMin) {
        hit = *end;
        hit.t = t;
        return true;
      }
    }
  return false;
}

std::vector<CsgSpan> CsgSolid::spans(const Ray& ray) const {
  Scratch& s = scratch();
  const float shift = lineSpans(*this, ray, s);
  std::vector<CsgSpan> out = s.result;
  for (CsgSpan& span : out) span.in.t += shift, span.out.t += shift;
  return out;
}

}  // namespace glint
