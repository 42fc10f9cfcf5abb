#pragma once
// Colours that vary over a surface: a constant, or the procedural 3D checker of seed 001 §9
// item 9. Every colour slot of a material (ka, kd, ks, km, ke) holds one.
#include "core/affine.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

struct ColorTexture {
  Rgb constant;
  bool checker = false;
  Rgb a, b;
  float scale = 1;

  static ColorTexture uniform(const Rgb& c) { return {c, false, {}, {}, 1}; }

  // At a render-space point: the checker is fixed in world space, so the point is moved back
  // by the scene's worldOrigin (in double) before the cells are counted.
  [[gnu::always_inline]] Rgb eval(const Vec3f& renderP, const Vec3d& worldOrigin) const {
    return checker ? checkerAt(renderP, worldOrigin) : constant;
  }
  [[gnu::always_inline]] bool isBlack() const {
    return checker ? a.isBlack() && b.isBlack() : constant.isBlack();
  }

 private:
  Rgb checkerAt(const Vec3f& renderP, const Vec3d& worldOrigin) const;
};

}  // namespace glint
