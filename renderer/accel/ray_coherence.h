#pragma once
// Ray coherence (Ohta & Maekawa 1987, seed 002 §9.2.4): for each ray origin — the eye, each
// light at a finite position, each world object whose material sends rays on (mirror, glossy,
// dielectric) — and each class of the subdivided direction cube, the list O[origin, class] of
// the objects whose visibility set from the origin meets the class (accel/visibility_sets.h),
// built before tracing. A ray that carries its origin (Ray::origin) tests only its list.
//
// Objects are the world group's entries: a sphere, quad, disk, CSG solid or instance, and a
// whole triangle mesh, which keeps a BoxTree of its triangles inside, so that a mesh of 10⁵
// triangles is one entry of each list it belongs to (O(m·n) lists over entries, not triangles)
// and a ray that meets it descends its tree (O(log n), not O(n)). Instanced groups keep a
// BoxTree each (two levels like the other backends; moving objects are bounded over the shutter).
//
// Rules of the query, each exact for any ray (DESIGN.md §3):
//  - a ray tagged with a world entry or the eye uses that origin's row only when its origin lies
//    in the origin's shell grown by half the pad; a ray tagged with light k only when tMax ≤ 1
//    and its point at t = 1 lies in the light's shell, and then it is classified from the light,
//    reversed (the segment lies on the ray from that point along −d);
//  - every other ray (no tag, an object that sends no rays on, an origin whose row the budget
//    left out, validate's random rays, any ray inside an instance) takes the fallback: the
//    BoxTree over the world's primitives.
// The pad is kRelativePad times the largest coordinate of the world, the eye and the lights
// (render space), which covers the offset spawned rays leave their surface by.
//
// Lists are sorted nearest first (a lower bound of the distance from the origin's shell), so a
// closest-hit query stops at the first object past its hit.
//
// Preprocessing is bounded (an attacker's scene with 10⁵ mirror spheres): rows are built in the
// order eye, lights, objects while origins × objects stays within kPairBudget visibility sets and
// the lists with their offsets within kWordBudget 32-bit words; the origins past either bound
// have no row (their rays take the fallback), which stats() reports.
#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/box_tree.h"
#include "accel/two_level.h"
#include "accel/visibility_sets.h"

namespace glint {

struct CoherenceStats {
  double buildSeconds = 0;
  size_t objects = 0;     // n: world entries in the lists
  size_t origins = 0;     // m: the eye, finite lights and objects that send rays on
  size_t rows = 0;        // origins given a row (the rest take the fallback)
  size_t classes = 0;     // d = 6·resolution²
  size_t pairs = 0;       // visibility sets computed
  size_t references = 0;  // entries over all lists
  size_t bytes = 0;       // lists, offsets, shells and trees
};

class RayCoherence final : public TwoLevelAccelerator<RayCoherence> {
 public:
  // The default resolution, ⌈2√n⌉ within [8, 256] for n objects: 6R² = 24n classes, so that a
  // class's list holds O(1) of the objects in view (docs/acceleration.md has the measurements).
  static constexpr int kMinResolution = 8, kMaxResolution = 256;
  static int defaultResolution(size_t objects) {
    const double r = std::ceil(2 * std::sqrt(double(objects)));
    return r < kMinResolution ? kMinResolution : r > kMaxResolution ? kMaxResolution : int(r);
  }
  static constexpr size_t kPairBudget = size_t(1) << 18;
  static constexpr size_t kWordBudget = size_t(1) << 24;  // 64 MiB of lists
  static constexpr double kRelativePad = 1e-4;

  // `resolution` classes along each edge of each face of the direction cube (0: the default,
  // defaultResolution).
  explicit RayCoherence(const Scene& scene, int resolution = 0, size_t pairBudget = kPairBudget,
                        size_t wordBudget = kWordBudget);
  std::string_view name() const override { return "coherence"; }
  const CoherenceStats& stats() const { return stats_; }

  // The row a ray uses and whether it is classified reversed; -1: the fallback. Exposed for the
  // tests.
  int rowOf(const Ray& ray, bool& reversed) const;
  // The objects of O[row, class]: world entries (group 0 indices).
  std::vector<uint32_t> list(int row, uint32_t directionClass) const;
  const DirectionClasses& classes() const { return classes_; }

 private:
  friend class TwoLevelAccelerator<RayCoherence>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;
  template <bool AnyHit, class Counter>
  bool inTree(const BoxTree& tree, uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
              Counter count) const;

  struct Object {
    uint32_t geom = 0;  // the world entry
    int tree = -1;      // a mesh's BoxTree in meshTrees_
  };
  struct Row {
    Shell origin;
    std::vector<uint32_t> offsets;  // list of class j: objects[offsets[j], offsets[j + 1])
    std::vector<uint32_t> objects;  // indices into objects_, nearest first
    std::vector<float> nearest;     // per entry: no hit on its object is closer to the origin
  };
  void buildRows(const std::vector<Shell>& origins, const std::vector<Shell>& targets,
                 size_t pairBudget, size_t wordBudget);

  DirectionClasses classes_;
  double pad_ = 0;
  std::vector<Object> objects_;
  std::vector<BoxTree> meshTrees_;
  std::vector<BoxTree> groupTrees_;  // per group; the world's is the fallback
  std::vector<Row> rows_;
  std::vector<int> rowOfEntry_;  // per world entry; -1: none
  std::vector<int> rowOfLight_;  // per light; -1: none
  int eyeRow_ = -1;
  CoherenceStats stats_;
};

}  // namespace glint
