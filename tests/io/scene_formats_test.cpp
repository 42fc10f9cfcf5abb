// The one table of formats Glint reads (io/scene_formats.h): a scene argument of another
// extension is refused naming what Glint reads, instead of being parsed as JSON ("invalid JSON
// ... last read: '<'" for a COLLADA file, before Collada was read).
#include "io/scene_formats.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/mesh_limits.h"

namespace glint {
namespace {

std::string refusal(const std::string& path) {
  try {
    sceneFileKind(path);
    return "(accepted)";
  } catch (const UsageError& e) {
    return e.what();
  }
}

TEST(SceneFormats, OtherExtensionsAreRefusedWithTheList) {
  // LightWave is one of Assimp's readers left out (docs/hardening.md, "Mesh formats").
  EXPECT_EQ(refusal("wuson.lwo"),
            "wuson.lwo: Glint does not read .lwo files; it reads Glint scenes (.json), OBJ (.obj), "
            "PLY (.ply), glTF 2.0 (.gltf, .glb), Collada (.dae), FBX (.fbx), 3DS (.3ds), AC3D "
            "(.ac), STL (.stl), Milkshape 3D (.ms3d) and X3D (.x3d)");
  EXPECT_NE(refusal("hang.OFF").find("does not read .off files"), std::string::npos);
  EXPECT_NE(refusal("shot.blend").find("does not read .blend files"), std::string::npos);
  EXPECT_NE(refusal("cubes.3mf").find("does not read .3mf files"), std::string::npos);
}

TEST(SceneFormats, TheTableDecidesWhatEachFileIs) {
  EXPECT_EQ(sceneFileKind("a/scene.json"), SceneFileKind::GlintScene);
  EXPECT_EQ(sceneFileKind("BOX.OBJ"), SceneFileKind::Mesh);
  EXPECT_EQ(sceneFileKind("box.ply"), SceneFileKind::Mesh);
  EXPECT_EQ(sceneFileKind("box.glb"), SceneFileKind::Gltf);
  // Formats whose cameras and lights Assimp reads, and one that has none.
  EXPECT_EQ(sceneFileKind("duck.DAE"), SceneFileKind::MeshScene);
  EXPECT_EQ(sceneFileKind("rig.fbx"), SceneFileKind::MeshScene);
  EXPECT_EQ(sceneFileKind("part.stl"), SceneFileKind::Mesh);
  // Assimp misplaces 3DS cameras (docs/scene-format.md): a 3DS file is framed by default.
  EXPECT_EQ(sceneFileKind("room.3DS"), SceneFileKind::Mesh);
  // A scene piped in (`<(generator)` is /dev/fd/63) has no extension: read as a Glint scene.
  EXPECT_EQ(sceneFileKind("/dev/fd/63"), SceneFileKind::GlintScene);
  // The mesh loader's list is the table's, less Glint's own scenes.
  EXPECT_EQ(meshFormatList(),
            "OBJ (.obj), PLY (.ply), glTF 2.0 (.gltf, .glb), Collada (.dae), FBX (.fbx), 3DS "
            "(.3ds), AC3D (.ac), STL (.stl), Milkshape 3D (.ms3d) and X3D (.x3d)");
  EXPECT_TRUE(isMeshExtension(".GLTF"));
  EXPECT_FALSE(isMeshExtension(".json"));
  EXPECT_TRUE(isMeshExtension(".dae"));
  EXPECT_FALSE(isMeshExtension(".lwo"));
}

}  // namespace
}  // namespace glint
