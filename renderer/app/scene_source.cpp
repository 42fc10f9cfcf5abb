#include "app/scene_source.h"

#include <default_scene.h>

#include "io/scene_loader.h"

namespace glint {

Scene loadSceneOrDefault(const std::string& path) {
  return path.empty() ? loadSceneText(kDefaultSceneJson, "<default scene>", kDefaultSceneDir)
                      : loadSceneFile(path);
}

}  // namespace glint
