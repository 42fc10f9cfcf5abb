#pragma once
// How wide a camera sample's footprint is where a ray of its tree hits: a ray cone
// (Akenine-Möller et al., "Texture Level of Detail Strategies for Real-Time Ray Tracing", Ray
// Tracing Gems ch. 20) without the curvature term. The camera's cone starts `widthAtEye` wide
// and widens by `spread` per unit distance; mirrors and glass pass it on as flat surfaces do,
// so its width at a hit is that linear function of the whole distance travelled from the eye,
// through every reflection and refraction: a texture seen in a flat mirror is filtered as
// sharply as seen directly at the same distance. (Curved mirrors widen the real cone faster;
// their reflections are filtered too little, never blurred.) Image textures filter over it;
// nothing else reads it, and scenes without image textures never compute it.
#include <algorithm>
#include <cmath>

#include "camera/camera.h"

namespace glint {

struct PixelCone {
  float widthAtEye = 0;
  float spread = 0;  // width gained per unit distance

  float widthAt(float distance) const { return widthAtEye + spread * distance; }
};

// The samples a pixel's footprint is shared among at the most: from this many on, each sample's
// footprint is 1/8 of the pixel's.
inline constexpr int kFinestFootprintSpp = 64;

// One camera sample's share of a pixel: the pixel's angle (or, orthographic, its width) divided
// by √spp, and no less than 1/8 of it, as pbrt scales its ray differentials: the samples of a
// pixel then cover it between them instead of each blurring over all of it.
inline PixelCone pixelCone(const CameraDesc& camera, int height, int spp) {
  const float share = 1.0f / std::sqrt(float(std::clamp(spp, 1, kFinestFootprintSpp)));
  // The window's height, as seen square-on (an oblique plane's pixels are a little wider).
  const ImageWindow window = camera.imageWindow(1, 1);
  const float pixel = (window.t - window.b) / float(height) * share;
  if (camera.projection == Projection::Orthographic) return {pixel, 0};
  return {0, pixel};
}

}  // namespace glint
