#pragma once
// Normal and bump maps: the shading normal bent by an image (docs/shading.md, "Normal and bump
// maps"), and the softening that keeps a bent normal from bringing back a shadow terminator.
//   - A normal map (glTF normalTexture, MTL norm, a scene's "normal_map") holds tangent-space
//     normals: texel c ∈ [0, 1]³ gives m = (2c − 1)·(scale, scale, 1), and the normal
//     m.x·T + m.y·B + m.z·N in the frame of the unmapped shading normal N, the tangent T (along
//     +u) and the bitangent B = sign·(N × T) (along +v; glTF's convention). Its texels are data,
//     read as the file stores them (ImageTexture::data), never sRGB-decoded.
//   - A bump map (MTL bump / map_Bump, a scene's "bump_map") holds heights h = scale × the
//     image's first channel, in world units along the normal: the displaced surface p + h·N has
//     tangents ∂p/∂u + (∂h/∂u)·N and ∂p/∂v + (∂h/∂v)·N, whose cross product is the bumped normal
//     (Blinn 1978; pbrt-v4's BumpMap, without its ∂N/∂u term).
// A material with both bends by the normal map first, then bumps that normal.
#include <memory>

#include "core/vec.h"
#include "geometry/shading_point.h"
#include "materials/image_texture.h"

namespace glint {

struct NormalMap {
  std::shared_ptr<const ImageTexture> image;  // null: none
  float scale = 1;                            // glTF's normalTexture.scale: on m.x and m.y
  UvTransform uvTransform;
};

struct BumpMap {
  std::shared_ptr<const ImageTexture> image;  // null: none
  float scale = 1;                            // world units per unit of the image
  UvTransform uvTransform;
};

struct ShadingMaps {
  NormalMap normal;
  BumpMap bump;
};

// The shading normal at sp bent by `maps`: unit, on the side of the geometric normal sp.ng (the
// rule sp.ns keeps: the mapped normal must not turn the surface around), starting from sp.ns.
// Reads sp.uv, sp.dpdu, sp.dpdv and sp.tangent. `wo` and `footprint`: the direction towards the
// viewer and the pixel's footprint width, over which the images are filtered (as colour
// textures are, materials/texture.h).
Vec3f mappedNormal(const ShadingMaps& maps, const ShadingPoint& sp, const Vec3f& wo,
                   float footprint);

// Chiang, Li and Burley, "Taming the Shadow Terminator" (SIGGRAPH 2019 talk), Cycles' "bump
// shadowing term": the factor on the light arriving along unit wi at a point whose normal
// `mapped` was bent away from `unmapped` (both unit, on the viewer's side). A bent normal faces
// lights that the surface it stands on faces less, or not at all; with g = cos(unmapped, wi) /
// (cos(mapped, wi)·cos(unmapped, mapped)), the fraction of microfacets a bent normal of that
// tilt would leave lit, the factor fades smoothly as −g³ + g² + g from 1 at g ≥ 1 to 0 at
// g ≤ 0 (its slope is 0 at g = 1, so light well above the horizon is left as it is). A light
// below the unmapped surface gets nothing, however the map bends the normal towards it.
[[gnu::always_inline]] inline float bumpShadowing(const Vec3f& unmapped, const Vec3f& mapped,
                                                  const Vec3f& wi) {
  const float cosMapped = dot(mapped, wi), cosBetween = dot(unmapped, mapped);
  if (!(cosMapped > 0 && cosBetween > 0)) return 0;
  const float g = dot(unmapped, wi) / (cosMapped * cosBetween);
  if (g >= 1) return 1;
  if (!(g > 0)) return 0;
  return g * (1 + g - g * g);
}

}  // namespace glint
