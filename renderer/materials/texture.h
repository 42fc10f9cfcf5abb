#pragma once
// Colours that vary over a surface. Every colour slot of a material (ka, kd, ks, km, ke) holds
// one: a constant; a solid pattern of the point blending two colours a and b (checker, noise,
// marble, wood: materials/procedural.h, seed 001 §9 item 9); or an image on the surface's
// (u, v) times a constant factor (MTL's Kd × map_Kd, glTF's baseColorFactor × texture),
// filtered over the pixel's footprint (materials/image_texture.h).
#include <memory>

#include "core/affine.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "geometry/shading_point.h"
#include "materials/image_texture.h"

namespace glint {

// VertexColor: the constant times the mesh's interpolated vertex colour (ShadingPoint).
enum class TexturePattern : uint8_t { Constant, Checker, Noise, Marble, Wood, Image, VertexColor };

// Where a texture is read: the shading point, the direction towards the viewer and the width
// of the pixel's footprint there (the integrators' ray cones, integrator/footprint.h); and the
// scene's worldOrigin, which solid patterns add back to the render-space point (in double), so
// that they stay fixed in world space.
struct TextureLookup {
  const ShadingPoint& sp;
  const Vec3f& wo;
  float footprint;
  const Vec3d& worldOrigin;
};

struct ColorTexture {
  TexturePattern pattern = TexturePattern::Constant;
  Rgb constant;     // the colour; for an image, the factor it is multiplied by
  Rgb a, b;         // a solid pattern's two colours
  float scale = 1;  // a solid pattern's feature size in world units
  std::shared_ptr<const ImageTexture> image;
  UvTransform uvTransform;
  bool timesVertexColor = false;  // an image also multiplied by the vertex colour (glTF COLOR_0)

  static ColorTexture uniform(const Rgb& c) {
    ColorTexture t;
    t.constant = c;
    return t;
  }

  [[gnu::always_inline]] Rgb eval(const TextureLookup& at) const {
    return pattern == TexturePattern::Constant ? constant : patternAt(at);
  }
  // The same with the lookup's parts: a constant (nearly every slot) reads none of them, and
  // the lookup is only assembled for a pattern.
  [[gnu::always_inline]] Rgb eval(const ShadingPoint& sp, const Vec3f& wo, float footprint,
                                  const Vec3d& worldOrigin) const {
    return pattern == TexturePattern::Constant ? constant
                                               : patternAt({sp, wo, footprint, worldOrigin});
  }
  [[gnu::always_inline]] bool isBlack() const {
    switch (pattern) {
      case TexturePattern::Constant:
      case TexturePattern::Image:
      case TexturePattern::VertexColor:
        return constant.isBlack();
      default:
        return a.isBlack() && b.isBlack();
    }
  }

 private:
  Rgb patternAt(const TextureLookup& at) const;
};

}  // namespace glint
