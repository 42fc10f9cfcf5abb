#include "app/scene_source.h"

#include <default_scene.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/file_names.h"
#include "io/scene_loader.h"

namespace glint {

namespace {

bool isMeshFile(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb";
}

// A mesh file given in place of a scene: the file with its own materials, lit by a directional
// light from above, front and left with a little ambient light, seen by a camera that frames its
// bounds from the front, right and above (+y up, +z towards the viewer, as glTF and most OBJ
// files have it). docs/scene-format.md, "A mesh file as the scene".
Scene meshFileAsScene(const std::string& path, std::optional<int> frame) {
  const std::filesystem::path file = std::filesystem::absolute(path);
  const nlohmann::json scene = {
      {"render", {{"ambient", {0.1, 0.1, 0.1}}, {"background", {0.18, 0.18, 0.2}}}},
      // Placed at the origin for loading (render space is then world space); aimed below.
      {"camera", {{"eye", {0, 0, 0}}, {"look_at", {0, 0, -1}}, {"vfov", 40}}},
      {"lights",
       {{{"type", "directional"}, {"direction", {-0.4, -1, -0.6}}, {"intensity", {1, 1, 1}}}}},
      {"objects", {{{"type", "mesh"}, {"file", file.filename().string()}}}}};
  Scene s = loadSceneText(scene.dump(), path, file.parent_path().string(), frame);
  const Bounds3f b = s.worldBounds();
  const Vec3f centre = 0.5f * (b.lo + b.hi);
  const float radius = std::max(0.5f * length(b.hi - b.lo), 1e-6f);
  // The bounding sphere fills the frame's height, with a tenth to spare.
  const float distance =
      1.1f * radius / std::sin(0.5f * s.cameraDesc.vfovDegrees * 3.14159265f / 180);
  s.cameraDesc.eye = centre + distance * normalize(Vec3f{0.5f, 0.4f, 1.0f});
  s.cameraDesc.lookAt = centre;
  s.cameraDesc.up = {0, 1, 0};
  s.cameraDesc.focusDistance = distance;
  return s;
}

}  // namespace

Scene loadSceneOrDefault(const std::string& path, std::optional<int> frame) {
  if (path.empty())
    return loadSceneText(kDefaultSceneJson, "<default scene>", kDefaultSceneDir, frame);
  return isMeshFile(path) ? meshFileAsScene(path, frame) : loadSceneFile(path, frame);
}

}  // namespace glint
