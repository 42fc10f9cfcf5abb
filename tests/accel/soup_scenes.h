#pragma once
// Random triangle soups and the scene text around them, for the hierarchies' agreement tests
// (the reference BVH and the sphere hierarchy): coordinates written with 9 significant digits
// so that the scene reads back the floats it was made from.
#include <sstream>
#include <string>

#include "core/hash.h"
#include "core/vec.h"

namespace glint::test {

inline float rnd(uint64_t key, int i, int k) { return toUnitFloat(hashKey(key, i, k)); }

inline std::string preciseVec(float x, float y, float z) {
  std::ostringstream s;
  s.precision(9);
  s << "[" << x << "," << y << "," << z << "]";
  return s.str();
}

// The eye at the world origin: render space (world − eye, io/placement.h) is world space.
inline std::string sceneWith(const std::string& objects, const std::string& groups = "") {
  return R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {"m": {"type": "phong"}}, )" +
         (groups.empty() ? "" : "\"groups\": {" + groups + "}, ") + "\"objects\": [" + objects +
         "]}";
}

// An inline mesh of `count` random triangles in [−1, 1]³ of edge up to `size`.
inline std::string soup(uint64_t key, int count, float size) {
  std::string pos, idx;
  for (int t = 0; t < count; ++t) {
    const Vec3f c{2 * rnd(key, t, 0) - 1, 2 * rnd(key, t, 1) - 1, 2 * rnd(key, t, 2) - 1};
    for (int v = 0; v < 3; ++v) {
      const Vec3f p = c + size * Vec3f{rnd(key, t, 3 + 3 * v) - 0.5f, rnd(key, t, 4 + 3 * v) - 0.5f,
                                       rnd(key, t, 5 + 3 * v) - 0.5f};
      pos += (pos.empty() ? "" : ",") + preciseVec(p.x, p.y, p.z);
    }
    idx += (idx.empty() ? "" : ",") + std::string("[") + std::to_string(3 * t) + "," +
           std::to_string(3 * t + 1) + "," + std::to_string(3 * t + 2) + "]";
  }
  return R"({"type": "mesh", "material": "m", "positions": [)" + pos + "], \"indices\": [" + idx +
         "]}";
}

}  // namespace glint::test
