#pragma once
// The scene a command works on: a scene file, a mesh file (framed by a default camera and lit by
// a default light, or a glTF file's own cameras and lights), or the bundled default scene when
// none is named; a file of a format Glint does not read (io/scene_formats.h) is refused.
#include <optional>
#include <string>

#include "scene/scene.h"

namespace glint {

// `frame`: the frame of an animated scene (default: its first); see io/animation.h.
// `cameraName`: a camera of a glTF, Collada, FBX or AC3D file (`--camera`); empty: the file's
// first camera, or the framing default. The SCENE argument's help, from the table of formats
// (io/scene_formats.h).
std::string sceneArgumentHelp();

// `environment`: an image file (`--environment`) that lights a mesh file in place of its
// default light and ambient light, as an environment light; a scene file declares its own, and
// is refused with it (UsageError).
Scene loadSceneOrDefault(const std::string& path, std::optional<int> frame = std::nullopt,
                         const std::string& cameraName = "", const std::string& environment = "");

}  // namespace glint
