#pragma once
// Scene files (../shared/SCENE_FORMAT.md, docs/scene-format.md) → an immutable Scene. Every
// user mistake throws SceneError naming file:line, the JSON path and the problem.
#include <string>

#include "scene/scene.h"

namespace glint {

Scene loadSceneFile(const std::string& path);
// `fileName` is used in messages; relative mesh paths resolve against `baseDir`.
Scene loadSceneText(const std::string& text, const std::string& fileName,
                    const std::string& baseDir);

}  // namespace glint
