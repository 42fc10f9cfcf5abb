// The axes an FBX file's GlobalSettings give, turned to Glint's (io/fbx_axes.h).
#include "io/fbx_axes.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace glint {
namespace {

// A scene with an empty root node and the six axis settings Assimp's FBX reader passes on.
struct FbxSettings {
  aiScene scene;
  FbxSettings(int32_t coord, int32_t coordSign, int32_t up, int32_t upSign, int32_t front,
              int32_t frontSign) {
    scene.mRootNode = new aiNode("root");
    scene.mMetaData = aiMetadata::Alloc(6);
    const int32_t values[6] = {coord, coordSign, up, upSign, front, frontSign};
    const char* keys[6] = {"CoordAxis",  "CoordAxisSign", "UpAxis",
                           "UpAxisSign", "FrontAxis",     "FrontAxisSign"};
    for (unsigned i = 0; i < 6; ++i) scene.mMetaData->Set(i, keys[i], values[i]);
  }
  aiVector3D placed(const aiVector3D& p) const { return scene.mRootNode->mTransformation * p; }
};

TEST(FbxAxes, AZUpFileStandsOnGlintsYAxis) {
  // 3ds Max's and Blender's axis_up 'Z': right +x, up +z, front -y. A 4-unit tower on the floor
  // rendered lying on its side; its top, (0, 0, 4) in the file, must stand at y = 4, and the
  // file's front (0, -1, 0) must face +z, as a Y-up file's does.
  FbxSettings zUp(0, 1, 2, 1, 1, -1);
  ASSERT_TRUE(turnFbxAxesToGlints(zUp.scene));
  const aiVector3D top = zUp.placed({0, 0, 4}), front = zUp.placed({0, -1, 0});
  EXPECT_EQ(top, aiVector3D(0, 4, 0));
  EXPECT_EQ(front, aiVector3D(0, 0, 1));
  EXPECT_EQ(zUp.placed({2, 0, 0}), aiVector3D(2, 0, 0));
  EXPECT_FLOAT_EQ(zUp.scene.mRootNode->mTransformation.Determinant(), 1);
}

TEST(FbxAxes, AYUpFileAndUnreadableSettingsAreLeftAsTheyAre) {
  // Right +x, up +y, front +z: every Y-up FBX of assimp-testmodels.
  FbxSettings yUp(0, 1, 1, 1, 2, 1);
  EXPECT_FALSE(turnFbxAxesToGlints(yUp.scene));
  EXPECT_TRUE(yUp.scene.mRootNode->mTransformation.IsIdentity());
  // Two settings naming the same axis, or a sign of 0: no turn can be read from them.
  FbxSettings sameAxis(0, 1, 2, 1, 2, 1), noSign(0, 1, 2, 0, 1, -1);
  EXPECT_FALSE(turnFbxAxesToGlints(sameAxis.scene));
  EXPECT_FALSE(turnFbxAxesToGlints(noSign.scene));
  EXPECT_TRUE(sameAxis.scene.mRootNode->mTransformation.IsIdentity());
  EXPECT_TRUE(noSign.scene.mRootNode->mTransformation.IsIdentity());
}

TEST(FbxAxes, ALeftHandedFileIsMirroredIntoGlintsAxes) {
  // Right -x, up +y, front +z: a left-handed frame, turned by a mirror (whose triangles
  // io/face_normals.h winds back outward).
  FbxSettings leftHanded(0, -1, 1, 1, 2, 1);
  ASSERT_TRUE(turnFbxAxesToGlints(leftHanded.scene));
  EXPECT_EQ(leftHanded.placed({-1, 0, 0}), aiVector3D(1, 0, 0));
  EXPECT_FLOAT_EQ(leftHanded.scene.mRootNode->mTransformation.Determinant(), -1);
}

}  // namespace
}  // namespace glint
