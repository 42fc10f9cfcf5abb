#pragma once
// The uniform grid of seed 000 §12.3.3 and seed 002 §9.2.1: a group's box cut into R × R × R
// equal cells (R = ⌈∛n⌉ for n primitives by default, the resolution of seed 002's analysis),
// each listing the primitives whose surface meets it (accel/surface_cell_overlap.h); a ray walks
// its cells in order with the 3D-DDA of Amanatides and Woo (1987) and stops at the first cell
// that holds its closest hit. Mailboxing skips a primitive already tested in an earlier cell.
// Two levels like the reference BVH: an instance is a primitive of its parent's grid and has a
// grid of its own group.
#include <array>
#include <cstdint>
#include <vector>

#include "accel/primitives.h"
#include "accel/two_level.h"
#include "core/bounds.h"

namespace glint {

struct GridStats {
  double buildSeconds = 0;
  size_t cells = 0, references = 0, primitives = 0;
  size_t bytes = 0;
};

class UniformGrid final : public TwoLevelAccelerator<UniformGrid> {
 public:
  // `resolution` cells per axis for every group; 0: ⌈∛n⌉ for a group of n primitives.
  explicit UniformGrid(const Scene& scene, int resolution = 0);
  std::string_view name() const override { return "grid"; }
  const GridStats& stats() const { return stats_; }

  struct Grid {
    Bounds3f box;
    std::array<int, 3> cells{1, 1, 1};
    Vec3f cellSize{0, 0, 0}, cellsPerUnit{0, 0, 0};  // 0 along an axis of no extent
    std::vector<uint32_t> cellStart;  // cell c's primitives: refs[cellStart[c], cellStart[c+1])
    std::vector<uint32_t> refs;       // indices into prims
    std::vector<PrimitiveBox> prims;
  };

 private:
  friend class TwoLevelAccelerator<UniformGrid>;
  template <bool AnyHit, class Counter>
  bool traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit, Counter count) const;

  std::vector<Grid> grids_;  // one per group
  GridStats stats_;
};

}  // namespace glint
