#pragma once
// The scene a command works on: a file, or the bundled default scene when none is named.
#include <string>

#include "scene/scene.h"

namespace glint {

Scene loadSceneOrDefault(const std::string& path);

}  // namespace glint
