#pragma once
// Constructive solid geometry (seed 000 §13.3; Roth 1982): closed solids combined by union,
// intersection and difference. Along a ray, each closed operand is "inside" over intervals of
// the line; a node combines its operands' intervals by its set operation; the combined solid's
// surface is where its intervals begin and end. Intervals thinner than a tolerance are dropped
// and gaps thinner than it closed, as the seed advises, so abutting operands leave no sliver
// and no seam. Shared by every backend (Embree user geometry, the reference BVH, the grid, the
// octree, the k-d tree, brute force): they differ only in how they reach the solid.
#include <array>
#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"
#include "geometry/hit.h"
#include "geometry/shapes.h"

namespace glint {

enum class CsgOp : uint8_t { Union, Intersection, Difference };

// A closed operand: a sphere, or a closed triangle mesh wound so that its normals point out.
struct CsgLeaf {
  bool isSphere = true;
  Sphere sphere;
  uint32_t firstTriangle = 0, triangleCount = 0;  // into CsgSolid::triangles
  uint32_t hierarchy = kInvalidId;                // a mesh's root in CsgSolid::meshNodes
  uint32_t materialId = 0;
  // Subtracted an odd number of times on the way to the root: its surface bounds the solid from
  // the other side, so the solid's outward normal is the operand's inward one.
  bool flipped = false;
};

struct CsgNode {
  CsgOp op = CsgOp::Union;
  uint32_t leaf = kInvalidId;      // a leaf node: index into CsgSolid::leaves
  std::vector<uint32_t> operands;  // an operation node: node indices (the first is the
                                   // minuend of a difference, the rest are subtracted)
  Bounds3f box;                    // contains the node's solid
};

// A node of a mesh operand's bounding volume hierarchy: a leaf lists triangles
// [first, first + count); an inner node's children are the next node and `second`.
struct CsgMeshNode {
  Bounds3f box;
  uint32_t first = 0, count = 0, second = 0;
};

// Which surface of the solid a hit is on (Hit::primId): a sphere leaf, or a mesh triangle.
struct CsgSurface {
  uint32_t leaf = 0;
  uint32_t triangle = kInvalidId;  // into CsgSolid::triangles; kInvalidId on a sphere
};

// One end of an inside interval: where along the ray, on which surface, at which barycentric
// (u, v) of a triangle (0 on spheres).
struct CsgBoundary {
  float t = 0;
  uint32_t surface = 0;
  float u = 0, v = 0;
};

struct CsgSpan {
  CsgBoundary in, out;
};

struct CsgSolid {
  std::vector<CsgNode> nodes;  // nodes[0] is the root
  std::vector<CsgLeaf> leaves;
  std::vector<std::array<Vec3f, 3>> triangles;
  // Every mesh operand's hierarchy (buildMeshHierarchies): a line meets a few of its triangles,
  // and testing them all made a render with an 82 000-triangle operand 77× slower.
  std::vector<CsgMeshNode> meshNodes;
  // Intervals (and gaps between them) thinner than this, in the solid's units, are rounding,
  // not shape (seed 000 §13.3: abutting operands).
  float thinness = 0;

  const Bounds3f& box() const { return nodes[0].box; }
  // Builds each mesh operand's hierarchy, reordering its triangles; once, before any ray.
  void buildMeshHierarchies();
  // Surface ids: sphere leaves are their leaf index; triangles follow all leaves.
  uint32_t surfaceId(uint32_t leaf, uint32_t triangle) const {
    return triangle == kInvalidId ? leaf : static_cast<uint32_t>(leaves.size()) + triangle;
  }
  CsgSurface surface(uint32_t id) const;
  // The solid's outward geometric normal on `surface` at `p` (not unit): the operand's own
  // outward normal, turned over where the operand is subtracted.
  Vec3f normal(const CsgSurface& surface, const Vec3f& p) const;

  // The first boundary of the solid along `ray` in (ray.tMin, ray.tMax); false when there is
  // none. Per-thread scratch buffers hold the intervals; they grow on the first deep solids a
  // thread meets and are reused after that, so the ray path does not allocate in steady state.
  bool intersect(const Ray& ray, CsgBoundary& hit) const;
  // All of the solid's inside intervals along the ray's whole line (t from −∞ to ∞), in order:
  // tests use it to check the combination against their own interval arithmetic.
  std::vector<CsgSpan> spans(const Ray& ray) const;
};

// Two sorted, disjoint interval lists combined by a set operation: the parts of the line inside
// `a` op `b`, with gaps and slivers up to `thin` (in t) closed and dropped. (Exposed for its
// unit test.)
void combineSpans(CsgOp op, const std::vector<CsgSpan>& a, const std::vector<CsgSpan>& b,
                  float thin, std::vector<CsgSpan>& out);

}  // namespace glint
