#pragma once
// The materials of mesh files, mapped onto Glint's surface model (materials/): an OBJ's MTL
// (Kd, Ks, Ns, Ka, Ke, Ni, illum), the same common keys of the other formats Assimp reads, and
// glTF 2.0's metallic-roughness factors with
// KHR_materials_transmission, _ior, _volume and _emissive_strength, with their image textures
// (map_Kd, map_Ks, map_Ke; glTF's base colour, metallic-roughness, occlusion and emissive
// textures, with their KHR_texture_transform, texCoord and sampler), and their normal and bump
// maps (MTL norm, bump / map_Bump with -bm; glTF's normalTexture with its scale). The table is
// in docs/scene-format.md ("Materials from mesh files").
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/gltf_subset.h"
#include "materials/material.h"

struct aiMaterial;

namespace glint {

// Other: any other format Assimp reads (Collada, FBX, 3DS, ...), through Assimp's common
// material keys (diffuse, specular, shininess, emissive, opacity and their textures).
enum class MeshFileFormat { Obj, Ply, Gltf, Other };

// Opens a texture a material names, its path as the file spells it; null where it cannot be
// read (the opener says why).
using TextureOpener = std::function<std::shared_ptr<const ImageTexture>(const std::string& named)>;

// A mesh file's vertex colour channels as Glint uses them: a negative or non-finite one reads as
// 0, and the mesh is warned of once it is read (as a material's colour would be), never
// replaced silently.
struct VertexColourChannels {
  uint64_t replaced = 0;
  float operator()(float c) {
    if (std::isfinite(c) && c >= 0) [[likely]]
      return c;
    ++replaced;
    return 0;
  }
  // The warning for `mesh` (its path) where any channel was replaced.
  void warnIfReplaced(const std::string& mesh) const;
};

// A part with vertex colours: they multiply its diffuse colour (an image's too, as glTF's
// COLOR_0 multiplies its base colour), and the ambient colour where it follows the diffuse.
void multiplyDiffuseByVertexColors(Surface& surface);

// The Glint material for `source`, named "FILE:NAME" (FILE the mesh file's name). A glTF
// material named by its gltfMaterialTag takes its name and texture transforms from
// `gltfMaterials` (io/gltf_subset.h).
Material materialFromMeshFile(const aiMaterial& source, MeshFileFormat format,
                              const std::string& fileName, const TextureOpener& openTexture,
                              const std::vector<GltfMaterialInfo>& gltfMaterials = {});

}  // namespace glint
