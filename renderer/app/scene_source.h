#pragma once
// The scene a command works on: a file, or the bundled default scene when none is named.
#include <optional>
#include <string>

#include "scene/scene.h"

namespace glint {

// `frame`: the frame of an animated scene (default: its first); see io/animation.h.
Scene loadSceneOrDefault(const std::string& path, std::optional<int> frame = std::nullopt);

}  // namespace glint
