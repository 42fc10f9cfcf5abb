#pragma once
// How an AC3D file asks its surfaces to be shaded, which Assimp's reader does not pass on: each
// SURF's flags mark it shaded smooth (0x10) or flat, and each OBJECT's `crease` line gives the
// angle (degrees) beyond which its smooth surfaces keep an edge. Assimp's reader gives no
// normals, so a smooth-shaded model rendered faceted.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <span>
#include <vector>

#include "core/vec.h"

namespace glint {

// The crease angle AC3D files give when they give none here: that of every AC3D file in
// assimp-testmodels but one (which gives 30).
inline constexpr double kDefaultAc3dCreaseDegrees = 45;

struct Ac3dShading {
  // Surfaces (polygons and triangle strips, not lines: SURF types 1 and 2) shaded each way.
  int smoothSurfaces = 0, flatSurfaces = 0;
  // The largest crease of the objects with smooth surfaces, and whether they differ.
  double creaseDegrees = 0;
  bool creasesDiffer = false;
};

// The shading the AC3D file read from `in` asks for, line by line as Assimp's reader reads it.
Ac3dShading readAc3dShading(std::istream& in);

// The most vertices at one position whose faces creaseNormals compares pairwise.
inline constexpr size_t kMaxCornersCompared = 256;

// Vertex normals for triangles (`triangles`: three indices each) whose vertices are their own
// corners, one per face, as Assimp's AC3D reader makes them: each vertex takes its face's normal
// plus those of the faces at the same position within `creaseDegrees` of it, normalised (the
// unweighted average of Assimp's smoothing step). Assimp's step compares every pair of vertices
// at a position, so a fan of a million triangles about one point would take 10^12 steps; here a
// position shared by more than kMaxCornersCompared vertices keeps its faces' own normals, and
// `crowded` counts such positions. A face of no area gives its vertices a zero normal, as the
// mesh's shading then takes its geometric normal.
std::vector<Vec3f> creaseNormals(std::span<const Vec3f> positions,
                                 std::span<const uint32_t> triangles, double creaseDegrees,
                                 size_t& crowded);

}  // namespace glint
