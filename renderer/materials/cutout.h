#pragma once
// An opacity cut-out (a scene's "opacity", MTL map_d, glTF alphaMode "MASK"): where a surface's
// coverage is below the cutoff, the surface is not there. A ray passes through such a hole as if
// nothing were there, so the intersection backends decide it (Scene::cutAway) and shading never
// sees the hit: camera rays, shadows, reflections and refractions all see the same holes. This is
// alpha testing, not blending: a coverage of 0.3 under a cutoff of 0.5 is a hole, 0.7 is solid.
#include <cstdint>
#include <memory>

#include "core/vec.h"
#include "materials/image_texture.h"

namespace glint {

struct Cutout {
  // What an image's coverage is: its alpha channel, an image without one being solid (glTF's
  // base colour alpha); or its alpha, else its first channel (a grey matte: MTL map_d, and the
  // scene's "opacity" image).
  enum class Channel : uint8_t { Alpha, AlphaElseGrey };

  float coverage = 1;  // the constant (MTL d, glTF baseColorFactor's alpha), times the image's
  std::shared_ptr<const ImageTexture> image;
  Channel channel = Channel::AlphaElseGrey;
  UvTransform uvTransform;
  float cutoff = 0.5f;

  // Whether some point of the surface can be a hole: only then do backends test it.
  bool active() const { return image != nullptr || coverage < cutoff; }

  // Whether the surface is absent at texture coordinates uv (origin at the image's bottom left,
  // as ShadingPoint::uv). The image is read at its finest level, unfiltered by any footprint: a
  // hole's outline does not move with the distance it is seen from.
  bool holeAt(Vec2f uv) const {
    if (!image) return coverage < cutoff;
    const Vec2f st = uvTransform.point(uv);
    const ImageFootprint at{{st.x, 1 - st.y}, {0, 0}, {0, 0}, uvTransform.wrapS, uvTransform.wrapT};
    return coverage * image->coverage(at, channel == Channel::AlphaElseGrey) < cutoff;
  }
};

}  // namespace glint
