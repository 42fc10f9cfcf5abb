#pragma once
// State shared by the parts of the loader while a Scene is assembled (internal to io/).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/json_source.h"
#include "io/placement.h"
#include "scene/scene.h"

namespace glint {

struct SceneBuilder {
  Scene scene;
  std::string baseDir;
  std::map<std::string, uint32_t> materialIds;
  std::map<std::string, uint32_t> groupIds;
  // Bounds of each group's contents, computed once however many instances place it.
  std::map<uint32_t, Bounds3f> groupBounds;
  // Instances inside groups, by the group that holds them. Debian's Embree has one instance
  // level (PLATFORM.md): when a group is placed, each instance it holds becomes a world-level
  // instance of its own, its transform composed in double (io/object_loader.cpp placeGroup).
  struct NestedInstance {
    uint32_t groupId;
    Affine local;    // the group's space ← the nested group's space
    JsonNode where;  // the instance's entry, for errors
  };
  std::map<uint32_t, std::vector<NestedInstance>> nested;
  // The world-level instances placing each group creates, once counted (io/object_loader.cpp).
  std::map<uint32_t, uint64_t> flattenedInstances;
  // Object names (Scene::objectNames) → their ids.
  std::map<std::string, uint32_t> objectIds;
  // The "name"s of objects and lights given so far → where each was given, for the error a
  // second one gets.
  std::map<std::string, std::string> givenNames;
  // While a world-level object is added: its "name", or "" when it has none. A mesh file's
  // named parts become objects of their own, "NAME/PART" (or "PART" for an unnamed object).
  // Unset for a group's members: the instance that places the group names them.
  std::optional<std::string> partPrefix;
  // Image textures by file and colour space: a file several materials use is opened once.
  std::map<std::pair<std::string, std::string>, std::shared_ptr<const ImageTexture>> textures;

  // The texture of `path` in `colorspace` (empty: the file's), opened on first use
  // (io/texture_file.h; throws as openImageTexture does).
  std::shared_ptr<const ImageTexture> texture(const std::string& path,
                                              const std::string& colorspace);

  // The object id of `name`, a new one the first time it is asked for.
  uint32_t objectIdOf(const std::string& name) {
    const auto [it, added] =
        objectIds.emplace(name, static_cast<uint32_t>(scene.objectNames.size()));
    if (added) scene.objectNames.push_back(name);
    return it->second;
  }
  // The checked "name" at `n` (io/object_names.h); a name given before is refused, naming
  // where.
  std::string claimName(const JsonNode& n);

  // World → render space (io/placement.h); set from the camera before anything is placed.
  Vec3f toRender(const JsonNode& worldPoint) const {
    return toFloat(worldPoint.vec3d() - scene.worldOrigin);
  }
  // An object's own transform followed by the shift into render space; groups keep their own
  // local space (the instance that places them is shifted instead).
  Affine placementOf(uint32_t groupId, const Affine& local) const {
    return groupId == 0 ? Affine::translate(Vec3d{} - scene.worldOrigin) * local : local;
  }
};

// Adds one entry of `objects` (groupId 0) or of a group to the scene (object_loader.cpp).
void addObject(SceneBuilder& b, const JsonNode& obj, uint32_t groupId, uint32_t objectId);
// Adds a "csg" entry placed by `place` (its own transform included) as one solid (csg_loader.cpp).
void addCsg(SceneBuilder& b, const JsonNode& obj, uint32_t groupId, uint32_t objectId,
            const Placement& place);
// In double; validated as a float transform (non-singular, affine).
Affine parseTransform(const JsonNode& node);
// The scene's "camera" at the animation's frame (camera_loader.cpp); `origin` is set to the
// eye's world position, which render space is placed around (io/placement.h).
void parseCamera(const JsonNode& n, const std::optional<Animation>& animation, CameraDesc& c,
                 Vec3d& origin);

}  // namespace glint
