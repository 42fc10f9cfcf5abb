#pragma once
// How far a scene may multiply itself. A glTF node listed twice as a child, or a JSON group
// placing the previous group twice, doubles what lies below it at each level: 40 levels of a
// 1 kB file name 2^40 copies. Glint flattens both (Embree has one instance level; Assimp
// pre-transforms a glTF's meshes), so the loaders count the copies from the graph first, with
// these helpers (counts multiply along paths and saturate instead of wrapping), and refuse a
// graph past its budget before anything is placed (docs/hardening.md, "Expansion").
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace glint {

// World-level instances one JSON scene may place (top-level instances and the nested ones that
// placeGroup flattens): each costs Glint's instance record and an Embree instance geometry, so
// the budget keeps a scene of them under a gigabyte (docs/hardening.md, "Expansion").
inline constexpr uint64_t kMaxFlattenedInstances = uint64_t{1} << 20;

// Triangles one mesh file may flatten to once every node's meshes are placed (Assimp copies a
// mesh for each node that places it): Assimp's import takes a few hundred bytes per triangle
// (docs/performance.md), so a few GB at the budget, the order of what a file within the 1 GiB
// limit can hold without sharing.
inline constexpr uint64_t kMaxFlattenedTriangles = uint64_t{1} << 24;

// a × b and a + b, held at UINT64_MAX instead of wrapping.
inline uint64_t saturatingMul(uint64_t a, uint64_t b) {
  if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a)
    return std::numeric_limits<uint64_t>::max();
  return a * b;
}
inline uint64_t saturatingAdd(uint64_t a, uint64_t b) {
  return b > std::numeric_limits<uint64_t>::max() - a ? std::numeric_limits<uint64_t>::max()
                                                      : a + b;
}

// "1099511627776", or "more than 18446744073709551614" for a saturated count.
std::string countText(uint64_t count);

// "a > b > c": the names of a path through a graph, the middle left out past `keep` names
// ("a > b > … (36 more) > y > z").
std::string pathText(const std::vector<std::string>& names, size_t keep = 8);

}  // namespace glint
