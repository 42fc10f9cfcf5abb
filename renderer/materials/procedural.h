#pragma once
// Solid textures: colours as equations of the hit point (seed 001 §9 item 9). Each is fixed
// in world space and returns a blend weight in [0, 1] between a texture's two colours a and b.
//   checker  cells of side 1 alternate (weight 0 or 1)
//   noise    Perlin's gradient noise (Perlin 2002, "Improving Noise"), mapped to [0, 1]
//   marble   veins: 0.5 + 0.5·sin(x + 5·turbulence), turbulence the sum of |noise| over octaves
//   wood     rings around the y axis, distorted by turbulence: the fraction of (radius + turb.)
// The point is in double (world space: render space plus the scene's origin), divided by the
// texture's scale before it gets here, so one unit is one feature.
#include "core/affine.h"

namespace glint {

float checkerPattern(const Vec3d& p);
// Perlin noise in [-1, 1]: zero at every lattice point, smooth (C2) between them.
float perlinNoise(const Vec3d& p);
// Σ over `octaves` of |noise(2^i p)| / 2^i: the fractal sum Perlin's marble is made of.
float turbulence(const Vec3d& p, int octaves = 6);
float noisePattern(const Vec3d& p);
float marblePattern(const Vec3d& p);
float woodPattern(const Vec3d& p);

}  // namespace glint
