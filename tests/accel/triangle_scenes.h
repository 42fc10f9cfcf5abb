#pragma once
// Triangle scenes built for the spatial subdivisions' rules and bounds (grid, octree, k-d tree).
#include <string>

#include "core/hash.h"
#include "test_util.h"

namespace glint::test {

inline std::string vec(float x, float y, float z) {
  return "[" + std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z) + "]";
}

// n small triangles scattered in the unit cube, or n long ones fanned across it (each from one
// corner region to the opposite: every box spans the whole cube).
inline Scene triangles(int n, bool fan) {
  std::string pos, idx;
  for (int t = 0; t < n; ++t) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(3, t, k)); };
    const float s = fan ? 1.0f : 0.01f;
    const float x = fan ? 0.01f * u(0) : u(0), y = fan ? 0.01f * u(1) : u(1), z = u(2);
    pos += (t ? "," : "") + vec(x, y, z) + "," + vec(x + s, y, z) + "," +
           vec(x + s, y + s, z + s * u(3));
    idx += (t ? ",[" : "[") + std::to_string(3 * t) + "," + std::to_string(3 * t + 1) + "," +
           std::to_string(3 * t + 2) + "]";
  }
  // The eye at the origin: render space (world minus the eye) is then world space.
  return sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0.5,0.5,0.5]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "mesh", "material": "m", "positions": [)" +
                       pos + "], \"indices\": [" + idx + "]}]}");
}

}  // namespace glint::test
