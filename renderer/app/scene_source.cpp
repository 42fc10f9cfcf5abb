#include "app/scene_source.h"

#include <default_scene.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "camera/camera.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/log.h"
#include "core/out_of_memory.h"
#include "io/gltf_scene.h"
#include "io/json_source.h"
#include "io/mesh_io.h"
#include "io/object_names.h"
#include "io/scene_formats.h"
#include "io/scene_loader.h"
#include "io/texture_file.h"

namespace glint {

namespace {

// glTF's photometric intensities (candela for point and spot lights, lux for directional
// ones) as Glint's: the seeds' surfaces reflect k_d · I · cos θ with no 1/π (docs/shading.md),
// so a physically lit Lambert surface of albedo k_d is matched by I / π.
constexpr double kGltfIntensityToGlint = 1 / M_PI;

nlohmann::json fileLight(const FileLight& l) {
  const double s = l.intensity * (l.photometric ? kGltfIntensityToGlint : 1);
  const nlohmann::json intensity = {l.color.r * s, l.color.g * s, l.color.b * s};
  if (l.type == FileLight::Type::Directional)
    return {{"type", "directional"},
            {"direction", {l.direction.x, l.direction.y, l.direction.z}},
            {"intensity", intensity}};
  nlohmann::json light = {{"type", "point"},
                          {"position", {l.position.x, l.position.y, l.position.z}},
                          {"intensity", intensity},
                          {"falloff", l.inverseSquare ? "inverse_square" : "none"}};
  if (l.type == FileLight::Type::Spot) {
    light["type"] = "spot";
    light["direction"] = {l.direction.x, l.direction.y, l.direction.z};
    // In degrees; outer ≤ 90 exactly, whatever π/2 · 180/π rounds to.
    light["inner_angle"] = std::min(l.innerConeAngle * 180 / M_PI, 90.0);
    light["outer_angle"] = std::min(l.outerConeAngle * 180 / M_PI, 90.0);
  }
  return light;
}

// The scene `meshFileAsScene` writes for the mesh file `path`, loaded. Its errors name what the
// user gave, not the written scene's lines: the --environment image, the mesh file itself (whose
// reader's message names it), or a light of the file by the JSON path it took (lights[i], the
// file's i-th light).
Scene loadMeshFileScene(const nlohmann::json& scene, const std::string& path,
                        const std::string& dir, std::optional<int> frame,
                        const std::string& environment) {
  try {
    return loadSceneText(scene.dump(), path, dir, frame);
  } catch (const SceneError& e) {
    const std::string environmentImage =
        "lights[" + std::to_string(scene["lights"].size() - 1) + "].image";
    if (!environment.empty() && e.path() == environmentImage)
      throw SceneError({"--environment " + environment, 0}, "", e.problem());
    throw SceneError({path, 0}, e.path() == "objects[0].file" ? "" : e.path(), e.problem());
  }
}

// A mesh file given in place of a scene: the file with its own materials. A glTF file's own
// lights (KHR_lights_punctual), or those of a Collada, FBX, ... file (io/scene_formats.h's
// MeshScene kind), light it and its own camera (`cameraName`, else its first) sees it;
// otherwise a directional light from above, front and left with a little ambient light,
// and a camera that frames its bounds from the front, right and above (+y up, +z towards the
// viewer, as glTF and most OBJ files have it). docs/scene-format.md, "A mesh file as the scene".
// With `environment`, that image lights it instead of the default light and ambient light, and
// rays that miss see it.
Scene meshFileAsScene(const std::string& path, std::optional<int> frame,
                      const std::string& cameraName, const std::string& environment) {
  const std::filesystem::path file = std::filesystem::absolute(path);
  const SceneFileKind kind = sceneFileKind(path);
  const FileSceneInfo own = kind == SceneFileKind::Gltf ? readGltfSceneInfo(file.string())
                            : kind == SceneFileKind::MeshScene
                                ? readMeshFileSceneInfo(file.string())
                                : FileSceneInfo{};
  nlohmann::json lights = nlohmann::json::array();
  std::set<std::string> lightNames;
  for (const FileLight& l : own.lights) {
    lights.push_back(fileLight(l));
    // Scene names are unique: a repeated one is numbered as Blender numbers its copies
    // ("Lamp.001"); a name no scene may give (empty, "lights[0]") leaves the light unnamed.
    if (!objectNameProblem(l.name).empty()) continue;
    std::string name = l.name;
    for (int copy = 1; lightNames.count(name); ++copy) {
      char suffix[16];
      std::snprintf(suffix, sizeof suffix, ".%03d", copy);
      name = l.name + suffix;
    }
    lightNames.insert(name);
    lights.back()["name"] = name;
  }
  nlohmann::json render = {{"ambient", {0.1, 0.1, 0.1}}, {"background", {0.18, 0.18, 0.2}}};
  if (!environment.empty()) {
    lights.push_back(
        {{"type", "environment"}, {"image", std::filesystem::absolute(environment).string()}});
    render = nlohmann::json::object();
  } else if (lights.empty()) {
    lights.push_back(
        {{"type", "directional"}, {"direction", {-0.4, -1, -0.6}}, {"intensity", {1, 1, 1}}});
  }
  const nlohmann::json scene = {
      {"render", render},
      // Placed at the origin for loading (render space is then world space); aimed below.
      {"camera", {{"eye", {0, 0, 0}}, {"look_at", {0, 0, -1}}, {"vfov", 40}}},
      {"lights", lights},
      {"objects", {{{"type", "mesh"}, {"file", file.filename().string()}}}}};
  Scene s = loadMeshFileScene(scene, path, file.parent_path().string(), frame, environment);
  if (!cameraName.empty() || !own.cameras.empty()) {
    const FileCamera* chosen = own.cameras.empty() ? nullptr : &own.cameras[0];
    if (!cameraName.empty()) {
      chosen = nullptr;
      std::string names;
      for (const FileCamera& c : own.cameras) {
        if (c.name == cameraName && !chosen) chosen = &c;
        names += (names.empty() ? "" : ", ") + inQuotes(c.name);
      }
      if (!chosen)
        throw UsageError("--camera " + inQuotes(cameraName) + ": " + path +
                         (names.empty() ? " has no cameras" : " has the cameras " + names));
    }
    CameraDesc& c = s.cameraDesc;
    c.eye = toFloat(chosen->eye);
    c.lookAt = toFloat(chosen->lookAt);
    c.up = toFloat(chosen->up);
    c.focusDistance = 1;
    if (chosen->orthographic) {
      // glTF's orthographic projection maps [−xmag, xmag] × [−ymag, ymag] onto the whole
      // image, whatever its size: the view spans exactly that, and an image whose aspect is
      // not xmag / ymag (--width, --height) has non-square pixels, as a camera "window" gives.
      c.projection = Projection::Orthographic;
      c.orthoHeight = float(2 * chosen->ymag);
      c.window = ImageWindow{float(-chosen->xmag), float(chosen->xmag), float(-chosen->ymag),
                             float(chosen->ymag)};
    } else if (chosen->xfovDegrees > 0) {
      // Only the horizontal angle is known: the vertical one follows the image's aspect.
      c.vfovDegrees = float(
          2 *
          std::atan(std::tan(chosen->xfovDegrees * M_PI / 360) * s.render.height / s.render.width) *
          180 / M_PI);
    } else {
      c.vfovDegrees = float(chosen->yfovDegrees);
    }
    const std::string camera = path + ": camera " + inQuotes(excerpt(chosen->name));
    // The camera's own aspect ratio, at the default height, within render.width's range.
    if (chosen->aspectRatio > 0) {
      const double width = std::round(s.render.height * chosen->aspectRatio);
      if (!(width >= 1 && width <= 1 << 15))
        throw UsageError(camera + ": its aspect ratio " + formatNumber(chosen->aspectRatio) +
                         " makes an image " + formatNumber(width) + " pixels wide at height " +
                         std::to_string(s.render.height) + "; an image is 1 to 32768 wide");
      s.render.width = int(width);
    }
    // What the scene format's camera is checked for as it loads (io/camera_loader.h).
    try {
      Camera check(c, s.render.width, s.render.height);
    } catch (const std::invalid_argument& e) {
      throw UsageError(camera + ": " + e.what());
    }
    return s;
  }
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

std::string sceneArgumentHelp() {
  return "Scene: " + sceneFormatList() +
         "; a mesh file gets a default camera and light (a glTF, Collada, FBX or AC3D file "
         "its own); omitted: the default scene";
}

Scene loadSceneOrDefault(const std::string& path, std::optional<int> frame,
                         const std::string& cameraName, const std::string& environment) {
  // Refused by its extension before anything is read.
  const bool glintScene = path.empty() || sceneFileKind(path) == SceneFileKind::GlintScene;
  if (!cameraName.empty() && glintScene)
    throw UsageError("--camera names a camera of a glTF, Collada, FBX or AC3D file; " +
                     (path.empty() ? std::string("the default scene") : path) +
                     " has the one camera its \"camera\" gives");
  if (!environment.empty()) {
    if (glintScene)
      throw UsageError("--environment " + environment +
                       ": adds an environment light to a mesh-file scene; " +
                       (path.empty() ? std::string("the default scene") : path) +
                       " declares its lights itself (a \"lights\" entry {\"type\": "
                       "\"environment\", \"image\": FILE})");
    try {
      checkInputFile(environment, kMaxTextureFileBytes, "environment image");
    } catch (const OutOfMemoryError&) {
      throw;
    } catch (const GlintError& e) {
      throw UsageError("--environment " + environment + ": " + e.what());
    }
  }
  if (path.empty())
    return loadSceneText(kDefaultSceneJson, "<default scene>", kDefaultSceneDir, frame);
  return out_of_memory::whileDoing("reading scene " + path, [&] {
    return glintScene ? loadSceneFile(path, frame)
                      : meshFileAsScene(path, frame, cameraName, environment);
  });
}

}  // namespace glint
