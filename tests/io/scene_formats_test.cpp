// The one table of formats Glint reads (io/scene_formats.h): a scene argument of another
// extension is refused naming what Glint reads, instead of being parsed as JSON ("invalid JSON
// ... last read: '<'" for a COLLADA file).
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
  EXPECT_EQ(refusal("duck.dae"),
            "duck.dae: Glint does not read .dae files; it reads Glint scenes (.json), OBJ (.obj), "
            "PLY (.ply) and glTF 2.0 (.gltf, .glb)");
  EXPECT_NE(refusal("rig.FBX").find("does not read .fbx files"), std::string::npos);
  EXPECT_NE(refusal("shot.blend").find("does not read .blend files"), std::string::npos);
}

TEST(SceneFormats, TheTableDecidesWhatEachFileIs) {
  EXPECT_EQ(sceneFileKind("a/scene.json"), SceneFileKind::GlintScene);
  EXPECT_EQ(sceneFileKind("BOX.OBJ"), SceneFileKind::Mesh);
  EXPECT_EQ(sceneFileKind("box.ply"), SceneFileKind::Mesh);
  EXPECT_EQ(sceneFileKind("box.glb"), SceneFileKind::Gltf);
  // A scene piped in (`<(generator)` is /dev/fd/63) has no extension: read as a Glint scene.
  EXPECT_EQ(sceneFileKind("/dev/fd/63"), SceneFileKind::GlintScene);
  // The mesh loader's list is the table's, less Glint's own scenes.
  EXPECT_EQ(meshFormatList(), "OBJ (.obj), PLY (.ply) and glTF 2.0 (.gltf, .glb)");
  EXPECT_TRUE(isMeshExtension(".GLTF"));
  EXPECT_FALSE(isMeshExtension(".json"));
  EXPECT_FALSE(isMeshExtension(".dae"));
}

}  // namespace
}  // namespace glint
