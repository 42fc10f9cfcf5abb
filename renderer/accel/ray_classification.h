#pragma once
// Ray classification (Arvo and Kirk 1987), as seed 002 §9.2.3 gives it. A ray is a point of a
// 5-D space: its origin in the cube E around a group, and its direction as a point of one face
// of the direction cube (the dominant axis and its sign; (u, v) the other two components over
// the dominant one's magnitude, in [−1, 1]). The hyperset H of a group is six 5-D hypercubes,
// one per face. A cell is split in two across its longest axis (E scaled to a unit cube, so
// that a width of w in any axis spreads a beam by about w across E); each half keeps the
// objects of its parent's candidate list whose box its beam — the rays of the cell, an
// unbounded polyhedral volume — meets. Cells are made lazily, by the threads that trace: a ray
// descends from its face's root (Classify, a binary search) and makes each half it needs that
// no ray needed before, until a list holds at most n_min objects or the cell is at most w_min
// wide in its narrowest axis (the seed's stopping rule); it then tests every object of its
// cell's list, in ascending order, and keeps the closest hit. Only the half a ray needs is
// made (the seed makes both at once): the other is made when, and if, some ray needs it.
//
// Rules that keep it exact and deterministic:
// - A ray is classified by where it enters E (its origin when inside; the start of its segment
//   when tMin > 0); a ray whose segment misses E misses the group. Objects are tested with the
//   ray as it is, never with the clipped one.
// - Lists are conservative (the beam test over-approximates the beam and pads the cell for
//   rounding), so every list a ray can end in holds every object the ray hits; with lists in
//   ascending order and a strictly-closer rule, the hit is the lowest-numbered of the closest
//   objects whichever cell answered: the same for any thread count and any order of splitting.
// - Memory is capped (RayClassSettings::capBytes): making a cell first reserves its bytes; past
//   the cap its parent answers for it for good, with its (longer, still conservative) list.
// - A thread makes a cell privately and publishes it with one compare-and-swap; a thread that
//   loses the race drops its copy (the same list) and descends into the winner's.
// - A ray whose direction is zero or not finite, or a group whose E is a point or not finite,
//   tests the group's whole list (what brute force does).
// Two levels like the other structures: an instance is an object of its parent group, and the
// object-space ray is classified in the hyperset of the instanced group. Motion: the objects'
// boxes cover the whole shutter.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "accel/primitives.h"
#include "accel/ray_classification_settings.h"
#include "accel/two_level.h"

namespace glint {

// What the lazy build has made so far (a snapshot; cells keep being made while rays are traced).
struct RayClassStats {
  size_t primitives = 0;
  size_t cells = 0;       // made while tracing (the six roots of each group not counted)
  size_t references = 0;  // in the lists they own (a cell with all its parent's shares it)
  size_t lazyBytes = 0;   // of those cells and lists: at most capBytes
  size_t capBytes = 0;
  size_t beamTests = 0;   // of the objects of parents' lists against their halves' beams
  size_t testBudget = 0;  // beamTests stays within it
  size_t fixedBytes = 0;  // the groups' object boxes and root lists, made when built
};

class RayClassification final : public TwoLevelAccelerator<RayClassification> {
 public:
  explicit RayClassification(const Scene& scene, const RayClassSettings& settings = {});
  ~RayClassification() override;
  std::string_view name() const override { return "rayclass"; }
  RayClassStats stats() const;
  const RayClassSettings& settings() const { return settings_; }

  // The cap when RayClassSettings::capBytes is 0: 256 MiB, plus 4 bytes per reference of
  // referenceBudget (accel/primitives.h) over all groups' objects (what the octree and the k-d
  // tree may hold in references). A cell's list is a copy of part of its parent's, so the cells
  // near the roots hold most of n each: the octree's budget alone is spent before a bundled
  // scene's camera rays reach short lists.
  static size_t defaultCapBytes(size_t primitives);

  struct Cell;
  struct Hyperset;

 private:
  friend class TwoLevelAccelerator<RayClassification>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;
  template <class Counter>
  const Cell* classify(const Hyperset& h, const Ray& ray, float tEnd, Counter count) const;
  Cell* makeChild(const Hyperset& h, int face, Cell& parent, int half, const double* lo,
                  const double* w) const;

  RayClassSettings settings_;
  size_t capBytes_ = 0;
  size_t testBudget_ = 0;
  std::vector<std::unique_ptr<Hyperset>> sets_;  // one per group
  mutable std::atomic<size_t> lazyBytes_{0}, cells_{0}, references_{0}, beamTests_{0};
};

}  // namespace glint
