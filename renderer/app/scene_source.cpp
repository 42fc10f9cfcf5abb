#include "app/scene_source.h"

#include <default_scene.h>

#include "io/scene_loader.h"

namespace glint {

Scene loadSceneOrDefault(const std::string& path, std::optional<int> frame) {
  return path.empty() ? loadSceneText(kDefaultSceneJson, "<default scene>", kDefaultSceneDir, frame)
                      : loadSceneFile(path, frame);
}

}  // namespace glint
