#pragma once
// State shared by the parts of the loader while a Scene is assembled (internal to io/).
#include <map>
#include <string>

#include "io/json_source.h"
#include "scene/scene.h"

namespace glint {

struct SceneBuilder {
  Scene scene;
  std::string baseDir;
  std::map<std::string, uint32_t> materialIds;
  std::map<std::string, uint32_t> groupIds;
};

// Adds one entry of `objects` (groupId 0) or of a group to the scene (object_loader.cpp).
void addObject(SceneBuilder& b, const JsonNode& obj, uint32_t groupId, uint32_t objectId);
Transform parseTransform(const JsonNode& node);

}  // namespace glint
