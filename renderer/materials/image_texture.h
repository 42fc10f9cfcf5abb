#pragma once
// An image on a surface's (u, v) coordinates. Materials see only this interface; the images
// themselves are read by OpenImageIO outside the shading layer (io/texture_file.h), filtered
// over the footprint by their MIP pyramid (materials/mip_pyramid.h), and colour-converted to
// scene-linear there.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/rgb.h"
#include "core/vec.h"
#include "geometry/shading_point.h"

namespace glint {

// How an image continues outside [0, 1] along one of its axes (glTF's sampler wrapS, wrapT):
// repeated, its edge texels extended, or repeated mirrored every other time.
enum class TextureWrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };

// Where on the image a lookup reads: (s, t) with t down from the top row, as image files store
// rows, and the pixel's footprint as two axes in the same units (the derivatives of (s, t)
// across the pixel; their lengths say how much of the image one pixel covers); and how the
// image continues beyond [0, 1] along s and t.
struct ImageFootprint {
  Vec2f st;
  Vec2f axisA, axisB;
  TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
};

class ImageTexture {
 public:
  virtual ~ImageTexture() = default;
  // The image's scene-linear colour filtered over the footprint; outside [0, 1]² the image
  // continues as the footprint's wrap modes say. Where a float file holds negative values,
  // which no colour does, each filtered channel is held at 0 (the first such lookup warns).
  virtual Rgb color(const ImageFootprint& at) const = 0;
  // The image's first three channels as the file stores them, filtered likewise but never
  // colour-converted (a grey image gives its one channel to all three): data such as normal,
  // height, metallic-roughness and occlusion maps, whose texels are not colours.
  virtual Rgb data(const ImageFootprint& at) const = 0;
  // The image as one number, as the file stores it (no colour conversion), filtered likewise:
  // its alpha channel; for an image without one, its first channel when `greyWithoutAlpha` (a
  // matte), else 1 (opaque). Opacity cut-outs read it (materials/cutout.h).
  virtual float coverage(const ImageFootprint& at, bool greyWithoutAlpha) const = 0;
  virtual const std::string& path() const = 0;
};

// How one texture reads the surface's coordinates: a 2×3 affine map of them (uv' = M·uv +
// offset: MTL's -s/-o options and glTF's KHR_texture_transform), which of the surface's sets
// it maps (glTF's texCoord: 0, or 1 for a mesh's second set, ShadingPoint::uv1) and how the
// image continues beyond [0, 1] (glTF's sampler). The identity on the first set, repeating, by
// default.
struct UvTransform {
  float m00 = 1, m01 = 0, m10 = 0, m11 = 1;
  Vec2f offset{0, 0};
  uint8_t uvSet = 0;
  TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;

  Vec2f point(Vec2f uv) const {
    return {m00 * uv.x + m01 * uv.y + offset.x, m10 * uv.x + m11 * uv.y + offset.y};
  }
  Vec2f vector(Vec2f d) const { return {m00 * d.x + m01 * d.y, m10 * d.x + m11 * d.y}; }

  // Scale, then rotate counter-clockwise by `radians`, then offset (KHR_texture_transform's
  // order; a glTF file's, given in its texture space whose v runs down, becomes one of these
  // with another offset: io/gltf_texture_transform.h).
  static UvTransform offsetRotateScale(Vec2f offset, float radians, Vec2f scale) {
    const float c = std::cos(radians), s = std::sin(radians);
    return {c * scale.x, -s * scale.y, s * scale.x, c * scale.y, offset};
  }
};

// The pixel's footprint on the surface at sp, mapped to the image through (u, v): a disc of
// diameter `width` across the ray arriving from unit wo, projected onto the surface (stretched
// by 1/cos along the ray's direction in the surface), carried into (u, v) by the inverse of the
// surface's tangents dp/du, dp/dv (of the set `transform` names), then through `transform`,
// with v flipped (t = 1 − v: (u, v) has its origin at the bottom left, images at the top); the
// footprint takes the transform's wrap modes.
ImageFootprint imageFootprint(const ShadingPoint& sp, const Vec3f& wo, float width,
                              const UvTransform& transform);

}  // namespace glint
