#include "accel/uniform_grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "accel/surface_cell_overlap.h"
#include "core/seconds_since.h"

namespace glint {

namespace {

// A primitive goes into every cell its box reaches, and this far (in cells) beyond: the DDA's
// float steps may place a ray a hair into the neighbouring cell at a boundary.
constexpr float kCellPad = 1e-4f;
constexpr int kMaxCellsPerAxis = 1024;
constexpr uint32_t kMailboxSize = 64;  // a power of two

// The cell along one axis holding coordinate x (clamped into the grid).
int cellOf(float x, const UniformGrid::Grid& g, int axis, float pad = 0) {
  if (g.cellsPerUnit[axis] == 0) return 0;
  const float c = (x - g.box.lo[axis]) * g.cellsPerUnit[axis] + pad;
  if (!(c > 0)) return 0;  // NaN too
  return std::min(static_cast<int>(c), g.cells[axis] - 1);
}

// ⌈∛n⌉ exactly: std::ceil(std::cbrt(27.0)) is 4, cbrt rounding 3 up to 3.0000000000000004.
int cubeRootRoundedUp(size_t n) {
  // Past kMaxCellsPerAxis³ the answer is clamped anyway (and r³ stays far inside int64_t).
  n = std::min(n, size_t(kMaxCellsPerAxis) * kMaxCellsPerAxis * kMaxCellsPerAxis);
  int64_t r = std::llround(std::cbrt(double(n)));
  while (r * r * r < int64_t(n)) ++r;
  while (r > 1 && (r - 1) * (r - 1) * (r - 1) >= int64_t(n)) --r;
  return static_cast<int>(std::min<int64_t>(r, kMaxCellsPerAxis));
}

// The cells of `g` for `r` cells per axis (one along a flat or unbounded axis).
void setResolution(UniformGrid::Grid& g, int r) {
  for (int a = 0; a < 3; ++a) {
    const float extent = g.box.hi[a] - g.box.lo[a];
    // A flat or unbounded extent (past float's range) gets one cell along that axis.
    const bool cut = extent > 0 && std::isfinite(extent);
    g.cells[a] = cut ? std::clamp(r, 1, kMaxCellsPerAxis) : 1;
    g.cellSize[a] = cut ? extent / float(g.cells[a]) : 0;
    g.cellsPerUnit[a] = cut ? float(g.cells[a]) / extent : 0;
  }
}

// Cell (x, y, z) of `g`, its faces where the DDA puts them (the whole box along an axis of one
// cell).
Bounds3f cellBox(const UniformGrid::Grid& g, const std::array<int, 3>& cell) {
  Bounds3f b = g.box;
  for (int a = 0; a < 3; ++a) {
    if (g.cellsPerUnit[a] == 0) continue;
    b.lo[a] = g.box.lo[a] + float(cell[size_t(a)]) * g.cellSize[a];
    if (cell[size_t(a)] + 1 < g.cells[a])
      b.hi[a] = g.box.lo[a] + float(cell[size_t(a)] + 1) * g.cellSize[a];
  }
  return b;
}

UniformGrid::Grid buildGrid(const Scene& scene, uint32_t groupId, std::vector<PrimitiveBox> prims,
                            int resolution) {
  UniformGrid::Grid g;
  for (const PrimitiveBox& p : prims) g.box.extend(p.box);
  int r = resolution > 0 ? resolution : cubeRootRoundedUp(prims.size());
  // Each primitive's range of cells (those its box reaches), at the finest resolution (from r
  // down by halves) whose ranges stay within referenceBudget (n·R³ ≈ n² for primitives
  // spanning the box); the exact tests below list it in fewer.
  std::vector<std::array<int, 6>> ranges(prims.size());
  const double allowed = referenceBudget(prims.size());
  while (true) {
    setResolution(g, r);
    double references = 0;
    for (size_t i = 0; i < prims.size(); ++i) {
      auto& rg = ranges[i];
      for (int a = 0; a < 3; ++a) {
        rg[size_t(a)] = cellOf(prims[i].box.lo[a], g, a, -kCellPad);
        rg[size_t(a) + 3] = cellOf(prims[i].box.hi[a], g, a, kCellPad);
      }
      references +=
          double(rg[3] - rg[0] + 1) * double(rg[4] - rg[1] + 1) * double(rg[5] - rg[2] + 1);
    }
    if (references <= allowed || r == 1) break;
    r = std::max(1, r / 2);
  }
  // Each primitive in the cells of its range that its surface meets (accel/
  // surface_cell_overlap.h): (cell, primitive) pairs, then a counting sort by cell.
  const auto cellIndex = [&](int x, int y, int z) {
    return (size_t(z) * size_t(g.cells[1]) + size_t(y)) * size_t(g.cells[0]) + size_t(x);
  };
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t i = 0; i < prims.size(); ++i) {
    const auto& rg = ranges[i];
    for (int z = rg[2]; z <= rg[5]; ++z)
      for (int y = rg[1]; y <= rg[4]; ++y)
        for (int x = rg[0]; x <= rg[3]; ++x)
          if (surfaceContact(scene, groupId, prims[i], cellBox(g, {x, y, z})) ==
              CellContact::Surface)
            pairs.emplace_back(uint32_t(cellIndex(x, y, z)), uint32_t(i));
  }
  const size_t cellCount = size_t(g.cells[0]) * size_t(g.cells[1]) * size_t(g.cells[2]);
  g.cellStart.assign(cellCount + 1, 0);
  for (const auto& [cell, prim] : pairs) ++g.cellStart[cell + 1];
  for (size_t c = 0; c < cellCount; ++c) g.cellStart[c + 1] += g.cellStart[c];
  g.refs.resize(g.cellStart[cellCount]);
  std::vector<uint32_t> filled(g.cellStart.begin(), g.cellStart.end() - 1);
  for (const auto& [cell, prim] : pairs) g.refs[filled[cell]++] = prim;
  g.prims = std::move(prims);
  return g;
}

}  // namespace

UniformGrid::UniformGrid(const Scene& scene, int resolution) : TwoLevelAccelerator(scene) {
  const auto start = std::chrono::steady_clock::now();
  grids_.resize(scene.groups.size());
  // Instanced groups first (they follow their parents): an instance's box is its group's box.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    std::vector<PrimitiveBox> prims =
        groupPrimitives(scene, uint32_t(g), [&](uint32_t child) { return grids_[child].box; });
    if (prims.empty()) continue;
    Grid& grid = grids_[g] = buildGrid(scene, uint32_t(g), std::move(prims), resolution);
    stats_.primitives += grid.prims.size();
    stats_.references += grid.refs.size();
    stats_.cells += grid.cellStart.size() - 1;
    stats_.bytes += grid.cellStart.size() * sizeof(uint32_t) + grid.refs.size() * sizeof(uint32_t) +
                    grid.prims.size() * sizeof(PrimitiveBox);
  }
  stats_.buildSeconds = secondsSince(start);
}

template <bool AnyHit, class Counter>
bool UniformGrid::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                           Counter count) const {
  const Grid& g = grids_[groupId];
  if (g.prims.empty()) return false;
  // The part of the ray inside the grid's box.
  const RaySlabs slabs(ray);
  const Vec3f& inv = slabs.inv;
  float tEnter = ray.tMin, tLeave = std::min(ray.tMax, hit.t);
  if (!slabTest(g.box, ray, slabs, tEnter, tLeave)) return false;
  // Amanatides and Woo: the cell where the ray enters, and per axis the distance to the next
  // cell boundary and between boundaries.
  const Vec3f entry = ray.o + tEnter * ray.d;
  int cell[3], step[3], end[3];
  float tNext[3], tDelta[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = cellOf(entry[a], g, a);
    if (g.cellsPerUnit[a] == 0 || ray.d[a] == 0) {
      step[a] = 0;
      tNext[a] = kInfinity;
      tDelta[a] = kInfinity;
      end[a] = -1;
      continue;
    }
    const bool up = ray.d[a] > 0;
    step[a] = up ? 1 : -1;
    end[a] = up ? g.cells[a] : -1;
    const float boundary = g.box.lo[a] + float(cell[a] + (up ? 1 : 0)) * g.cellSize[a];
    tNext[a] = (boundary - ray.o[a]) * inv[a];
    tDelta[a] = g.cellSize[a] * std::fabs(inv[a]);
  }
  uint32_t mailbox[kMailboxSize];
  std::fill(mailbox, mailbox + kMailboxSize, std::numeric_limits<uint32_t>::max());
  bool found = false;
  while (true) {
    count.step();
    const size_t c = (size_t(cell[2]) * size_t(g.cells[1]) + size_t(cell[1])) * size_t(g.cells[0]) +
                     size_t(cell[0]);
    for (uint32_t k = g.cellStart[c]; k < g.cellStart[c + 1]; ++k) {
      const uint32_t i = g.refs[k];
      uint32_t& slot = mailbox[i & (kMailboxSize - 1)];
      if (slot == i) continue;  // tested in an earlier cell: its answer stands
      slot = i;
      count.test();
      const PrimitiveBox& p = g.prims[i];
      if (intersectPrimitive(scene_, groupId, p.geom, p.prim, ray, instId, hit,
                             intoInstance(count))) {
        if constexpr (AnyHit) return true;
        found = true;
      }
    }
    const int axis =
        tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
    // The closest hit so far lies before the next cell: no later cell holds a closer one.
    if (found && hit.t <= tNext[axis]) break;
    if (tNext[axis] > tLeave) break;
    cell[axis] += step[axis];
    if (step[axis] == 0 || cell[axis] == end[axis]) break;
    tNext[axis] += tDelta[axis];
  }
  return found;
}

}  // namespace glint
