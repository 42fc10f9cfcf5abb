#pragma once
// The files Glint reads, in one table: a command's SCENE argument and a scene's mesh "file" are
// read only when their extension is here, and refused otherwise with the list of what is.
// Before, a scene argument of any other extension was read as JSON ("invalid JSON ... last
// read: '<'" for a COLLADA file). A format added here is offered by every command and by the
// mesh loader (io/mesh_io.h routes it to its reader).
#include <string>

namespace glint {

enum class SceneFileKind {
  GlintScene,  // Glint's JSON scene (docs/scene-format.md)
  Mesh,        // a mesh file, read through Assimp or Glint's PLY reader, framed by defaults
  Gltf,        // a glTF 2.0 file: a mesh file whose own cameras and lights are used
  MeshScene,   // a mesh file whose own cameras and lights Assimp reads (io/mesh_io.h)
};

struct SceneFormat {
  const char* extension;  // lower case, with its dot
  const char* name;       // for messages; formats of one name are listed together
  SceneFileKind kind;
};

inline constexpr SceneFormat kSceneFormats[] = {
    {".json", "Glint scenes", SceneFileKind::GlintScene},
    {".obj", "OBJ", SceneFileKind::Mesh},
    {".ply", "PLY", SceneFileKind::Mesh},
    {".gltf", "glTF 2.0", SceneFileKind::Gltf},
    {".glb", "glTF 2.0", SceneFileKind::Gltf},
    // Assimp's readers that held under Glint's hostile-input checks (docs/hardening.md, "Mesh
    // formats": which were left out, and why).
    {".dae", "Collada", SceneFileKind::MeshScene},
    {".fbx", "FBX", SceneFileKind::MeshScene},
    {".3ds", "3DS", SceneFileKind::Mesh},
    {".ac", "AC3D", SceneFileKind::MeshScene},
    {".stl", "STL", SceneFileKind::Mesh},
    {".ms3d", "Milkshape 3D", SceneFileKind::Mesh},
    {".x3d", "X3D", SceneFileKind::Mesh},
};

// The format of `path` by its extension (any case); nullptr when the table has none.
const SceneFormat* findSceneFormat(const std::string& path);

// What a command's SCENE argument is. A path without an extension is a Glint scene (a scene
// piped in, as /dev/fd/63 from `<(generator)`); any other extension not in the table is a
// UsageError naming the file and what Glint reads.
SceneFileKind sceneFileKind(const std::string& path);

// "Glint scenes (.json), OBJ (.obj), PLY (.ply), glTF 2.0 (.gltf, .glb), ..."; with
// `meshesOnly`, the formats a scene's mesh "file" may have.
std::string sceneFormatList(bool meshesOnly = false);

}  // namespace glint
