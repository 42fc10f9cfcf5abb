#pragma once
// Rays that carry their origin (Ray::origin) as the integrators' rays do, cast at random: what
// `glint validate` and the tests check ray coherence (accel/ray_coherence.h) on beyond the
// rays of one render, every backend against Embree alike.
#include <cstdint>

#include "accel/accelerator.h"

namespace glint {

class Scene;

// For each of `count` samples: a ray from the eye (a point of a perspective camera's lens) in a
// random direction; and, from a point where a random ray towards a random world entry's box
// hits (found by `finder`, not asked of `accel`: a random ray that ends on a surface is no ray a
// renderer casts), a ray leaving that surface in a random direction and a shadow segment
// towards a random point of a random light at a finite position. Each is asked of `accel` as a
// closest-hit and an occlusion query.
void castOriginRays(const Scene& scene, const Accelerator& finder, const Accelerator& accel,
                    int count, uint64_t seed);

}  // namespace glint
