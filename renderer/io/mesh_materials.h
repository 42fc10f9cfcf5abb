#pragma once
// The materials of mesh files, mapped onto Glint's surface model (materials/): an OBJ's MTL
// (Kd, Ks, Ns, Ka, Ke, Ni, illum) and glTF 2.0's metallic-roughness factors with
// KHR_materials_transmission, _ior, _volume and _emissive_strength. The table is in
// docs/scene-format.md ("Materials from mesh files"). Textures are not mapped yet.
#include <string>

#include "materials/material.h"

struct aiMaterial;

namespace glint {

enum class MeshFileFormat { Obj, Ply, Gltf };

// The Glint material for `source`, named "FILE:NAME" (FILE the mesh file's name).
Material materialFromMeshFile(const aiMaterial& source, MeshFileFormat format,
                              const std::string& fileName);

}  // namespace glint
