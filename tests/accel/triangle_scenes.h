#pragma once
// Triangle scenes built for the spatial subdivisions' rules and bounds (grid, octree, k-d tree).
#include <gtest/gtest.h>

#include <string>

#include "accel/accelerator.h"
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

// `accel` finds brute force's closest hit on a ray down through triangles(n, true)'s fan, below
// its diagonal where every triangle lies.
inline void expectFindsTheFansClosestHit(const Scene& fan, const Accelerator& accel) {
  const auto brute = makeAccelerator(AccelKind::BruteForce, fan);
  const Ray r{{0.6f, 0.4f, 5}, {0, 0, -1}};
  const Hit a = accel.intersect(r), b = brute->intersect(r);
  ASSERT_TRUE(b);
  ASSERT_TRUE(a);
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.primId, b.primId);
}

}  // namespace glint::test
