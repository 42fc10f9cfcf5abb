#pragma once
// The cameras and lights of a file Assimp read (aiScene::mCameras, mLights: a Collada, FBX or
// AC3D file's), in world space: each is placed by the node of its name, through the
// node's parents, as Assimp's readers define them (a camera looks along mLookAt with mUp up in
// its node's frame; mHorizontalFOV is the full horizontal angle, as every reader of Assimp 5.2
// writes it, whatever its header says).
#include <string>

#include "io/file_scene_info.h"

struct aiScene;

namespace glint {

// Throws UsageError naming `path` and the camera or light whose placement or values are not
// usable (a singular or non-finite transform, a field of view outside (0°, 180°), a negative or
// non-finite colour). Ambient and area lights are left out with a warning, as is an attenuation
// Glint does not render (it renders none or 1/r²).
FileSceneInfo sceneInfoFromAssimp(const aiScene& scene, const std::string& path);

}  // namespace glint
