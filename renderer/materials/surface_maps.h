#pragma once
// What of the general surface (materials/surface.h) varies over it by an image's data channels
// where the model has no colour slot for it: glTF's metallic-roughness map (per texel, the base
// colour splits between the diffuse dielectric and the mirroring metal, and the roughness sets
// the highlight's exponent and the mirror's gloss) and its occlusion map (on the ambient term).
// The images are data: read as stored, never colour-converted. A surface without maps holds
// none and pays one test per hit.
#include <algorithm>
#include <memory>

#include "materials/image_texture.h"

namespace glint {

struct SurfaceMaps {
  // Metallic m = metallicFactor × the image's blue, roughness r = roughnessFactor × its green
  // (glTF). Where it is set, the surface's k_d is the base colour b and k_s the dielectric's
  // highlight colour: the point reads k_d = b·(1 − m), k_s = k_s·(1 − m) + b·m, k_m = b·m,
  // exponent = blinnPhongExponent(r) and gloss r.
  std::shared_ptr<const ImageTexture> metallicRoughness;
  UvTransform metallicRoughnessUv;
  float metallicFactor = 1, roughnessFactor = 1;
  // The ambient term times 1 + strength·(R − 1), R the image's red (glTF's occlusion).
  std::shared_ptr<const ImageTexture> occlusion;
  UvTransform occlusionUv;
  float occlusionStrength = 1;
};

// The Blinn-Phong exponent matching the GGX width α = roughness² (α at least 0.01), 2/α² − 2,
// clamped to [1, 10⁴].
inline float blinnPhongExponent(float roughness) {
  const float alpha = std::max(roughness * roughness, 1e-2f);
  return std::clamp(2 / (alpha * alpha) - 2, 1.0f, 1e4f);
}

}  // namespace glint
