#pragma once
// glTF's KHR_texture_transform (offset, rotation, scale) on the textures Glint reads from a glTF
// file, as the UvTransform Glint applies to a surface's (u, v) (materials/image_texture.h).
// glTF's texture coordinates have their origin at the image's top left; Glint's at the bottom
// left (Assimp flips v on import, v = 1 − v_glTF; images are read at t = 1 − v), so the glTF
// transform A becomes F∘A∘F in Glint, with F(u, v) = (u, 1 − v).
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "materials/image_texture.h"

namespace glint {

// Glint's transform for the glTF one A(uv) = T·R·S·uv: S scales by `scale`, T adds `offset`,
// and R turns by `rotation` radians counter-clockwise in glTF's texture space, whose v runs
// down: u' = cos·u + sin·v, v' = −sin·u + cos·v. The extension's prose and its example (offset
// [0, 1], rotation π/2, scale ½ reads the lower left quadrant), Khronos's sample viewer, three.js,
// Babylon.js, Blender and Cesium agree; the GLSL listing in its README has the opposite sign
// (KhronosGroup/glTF issue 1563).
UvTransform uvTransformFromGltf(Vec2f offset, float rotation, Vec2f scale);

// Values of magnitude above this are refused: a float texture coordinate that large no longer
// tells texels apart.
constexpr double kMaxGltfUvTransformValue = 1e4;

// The transform the KHR_texture_transform object `extension` gives (JSON null where the
// textureInfo has none: the identity), on the textureInfo's coordinate set `uvSet`. Malformed
// (not an object; offset or scale not two numbers, rotation not a number; a value not finite or
// beyond kMaxGltfUvTransformValue), it is warned about, naming `where`, and ignored: the
// identity. Its texCoord 0 or 1 replaces the textureInfo's set (the extension's rule); another
// is warned about and ignored (Glint reads TEXCOORD_0 and TEXCOORD_1).
UvTransform gltfTextureTransform(const nlohmann::json& extension, const std::string& where,
                                 int uvSet = 0);

}  // namespace glint
