#pragma once
// Shadow rays from a flat triangle of a smooth-shaded mesh leave from a point lifted towards the
// smooth surface its vertex normals stand for (Hanika, "Hacking the Shadow Terminator", Ray
// Tracing Gems II, ch. 4). From the facet itself, a light that the interpolated normal faces
// but the facet does not is blocked by the neighbouring facets: the mesh shadows itself in
// blocks along its terminator.
#include "core/vec.h"

namespace glint {

// The lift of point `p` = Σ b_i·v_i of triangle (v_0, v_1, v_2) with unit vertex normals n_i,
// towards the side `side` (any vector on the side the rays leave to). Each vertex's tangent
// plane (through v_i, normal n_i turned to `side`) bounds the smooth surface near it; where p
// lies below one, it is moved up onto it, and the moves are blended by the barycentrics. Zero
// where p is above every tangent plane: a concave or flat part is not lifted. The lift never
// exceeds the triangle's deviation from its vertices' tangent planes, so it stays within the
// facet's own bulge.
inline Vec3f smoothSurfaceLift(const Vec3f& p, const Vec3f (&v)[3], const Vec3f (&n)[3],
                               const float (&b)[3], const Vec3f& side) {
  Vec3f lift{0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const Vec3f ni = dot(n[i], side) < 0 ? -n[i] : n[i];
    const float below = dot(p - v[i], ni);
    if (below < 0) lift -= (b[i] * below) * ni;
  }
  return lift;
}

}  // namespace glint
