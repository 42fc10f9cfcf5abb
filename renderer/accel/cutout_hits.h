#pragma once
// The first hit a shape keeps when its material has an opacity cut-out (materials/cutout.h):
// every backend, and the shared plane loop, finds it the same way, so all agree on the holes.
#include "scene/scene.h"

namespace glint {

// `test(ray, u, v)` is the shape's first hit in (ray.tMin, ray.tMax) (kInfinity for none), as
// the shared tests in geometry/shapes.h give it; `r` is in the space of g's group. A hit in a
// hole is passed over and the shape tested again beyond it: through a hole in a sphere's near
// side its far side shows.
template <class Test>
[[gnu::always_inline]] inline float firstKeptHit(const Scene& scene, const Geometry& g,
                                                 uint32_t prim, Ray r, float& u, float& v,
                                                 Test&& test) {
  const bool cut = scene.hasCutout(g);
  // No shape meets a ray more than twice, so a third test finds nothing. (One call of `test`
  // in the loop: a second one keeps GCC from inlining the shape tests.)
  for (int tries = 0;; ++tries) {
    const float t = test(r, u, v);
    if (!cut || !(t < r.tMax) || !scene.cutAway(g, r, t, prim, u, v)) return t;
    if (tries == 2) return kInfinity;
    r.tMin = t;  // every test wants t > tMin: the next hit is beyond this one
  }
}

}  // namespace glint
