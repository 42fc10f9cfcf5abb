#include "io/gltf_scene.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/error.h"
#include "core/file_names.h"
#include "core/input_files.h"
#include "io/gltf_expansion.h"
#include "io/gltf_subset.h"
#include "io/mesh_limits.h"

namespace glint {

namespace {

using nlohmann::json;

class Reader {
 public:
  Reader(std::string path, json doc) : path_(std::move(path)), doc_(std::move(doc)) {}

  FileSceneInfo read() {
    const json* nodes = array("nodes");
    if (!nodes) return info_;
    const json* scenes = array("scenes");
    size_t sceneIndex = 0;
    if (const auto it = doc_.find("scene"); it != doc_.end()) sceneIndex = index(*it, "scene");
    std::vector<size_t> roots;
    if (scenes && sceneIndex < scenes->size()) {
      const json& scene = (*scenes)[sceneIndex];
      if (const auto n = scene.find("nodes"); n != scene.end() && n->is_array())
        for (const json& i : *n)
          roots.push_back(index(i, "scenes[" + std::to_string(sceneIndex) + "].nodes"));
    } else {
      // No scene: glTF says the file is a library; Glint shows every node without a parent.
      std::vector<bool> isChild(nodes->size());
      for (const json& node : *nodes)
        if (const auto c = node.find("children"); c != node.end() && c->is_array())
          for (const json& i : *c)
            if (i.is_number_unsigned() && i.get<size_t>() < isChild.size())
              isChild[i.get<size_t>()] = true;
      for (size_t i = 0; i < nodes->size(); ++i)
        if (!isChild[i]) roots.push_back(i);
    }
    std::vector<bool> onPath(nodes->size());
    for (size_t root : roots) visit(*nodes, root, Affine{}, onPath, 0);
    nameCamerasApart();
    return info_;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw UsageError("glTF " + path_ + ": " + what);
  }

  const json* array(const char* key) const {
    const auto it = doc_.find(key);
    if (it == doc_.end()) return nullptr;
    if (!it->is_array()) fail(std::string(key) + " is not an array");
    return &*it;
  }

  size_t index(const json& j, const std::string& where) const {
    if (!j.is_number_unsigned()) fail(where + " is not an index");
    return j.get<size_t>();
  }

  double number(const json& object, const char* key, double otherwise,
                const std::string& where) const {
    const auto it = object.find(key);
    if (it == object.end()) return otherwise;
    if (!it->is_number() || !std::isfinite(it->get<double>()))
      fail(where + "." + key + " is not a finite number");
    return it->get<double>();
  }

  std::vector<double> numbers(const json& object, const char* key, size_t count,
                              const std::string& where) const {
    const auto it = object.find(key);
    if (it == object.end()) return {};
    if (!it->is_array() || it->size() != count)
      fail(where + "." + key + " must hold " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (const json& v : *it) {
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        fail(where + "." + key + " holds a value that is not a finite number");
      out.push_back(v.get<double>());
    }
    return out;
  }

  // The node's own transform: its matrix (column-major in the file), else T · R · S.
  Affine localTransform(const json& node, const std::string& where) const {
    if (const std::vector<double> m = numbers(node, "matrix", 16, where); !m.empty())
      return Affine::fromRows(
          {m[0], m[4], m[8], m[12], m[1], m[5], m[9], m[13], m[2], m[6], m[10], m[14]});
    Affine t;
    if (const auto v = numbers(node, "translation", 3, where); !v.empty())
      t = Affine::translate({v[0], v[1], v[2]});
    if (const auto q = numbers(node, "rotation", 4, where); !q.empty()) {
      const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (!(n > 0)) fail(where + ".rotation is a zero quaternion");
      const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
      t = t *
          Affine::fromRows({1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0,
                            2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0,
                            2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0});
    }
    if (const auto s = numbers(node, "scale", 3, where); !s.empty())
      t = t * Affine::scale({s[0], s[1], s[2]});
    return t;
  }

  void visit(const json& nodes, size_t i, const Affine& parent, std::vector<bool>& onPath,
             int depth) {
    const std::string where = "nodes[" + std::to_string(i) + "]";
    if (i >= nodes.size())
      fail(where + " does not exist (" + std::to_string(nodes.size()) + " nodes)");
    if (onPath[i]) fail(where + " is its own ancestor (the node tree has a cycle)");
    if (depth > kMaxGltfNodeDepth)
      fail("the node tree is deeper than " + std::to_string(kMaxGltfNodeDepth) + " levels");
    const json& node = nodes[i];
    if (!node.is_object()) fail(where + " is not an object");
    const Affine world = parent * localTransform(node, where);
    const std::string nodeName =
        node.contains("name") && node["name"].is_string() ? node["name"].get<std::string>() : "";
    if (const auto c = node.find("camera"); c != node.end()) {
      addCamera(index(*c, where + ".camera"), world, nodeName);
      cameraNodes_.push_back(where);
    }
    if (const auto e = node.find("extensions"); e != node.end() && e->is_object())
      if (const auto l = e->find("KHR_lights_punctual"); l != e->end() && l->is_object())
        if (const auto li = l->find("light"); li != l->end())
          addLight(index(*li, where + ".extensions.KHR_lights_punctual.light"), world, nodeName);
    onPath[i] = true;
    if (const auto c = node.find("children"); c != node.end()) {
      if (!c->is_array()) fail(where + ".children is not an array");
      for (const json& child : *c)
        visit(nodes, index(child, where + ".children"), world, onPath, depth + 1);
    }
    onPath[i] = false;
  }

  // The node's origin, and its −z and +y axes, in world space.
  struct Frame {
    Vec3d origin, forward, up;
  };
  Frame frameOf(const Affine& world, const std::string& where) const {
    Frame f;
    f.origin = world.point({0, 0, 0});
    const auto unit = [&](const Vec3d& v) {
      const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
      if (!(n > 0) || !std::isfinite(n))
        fail(where + "'s node transform is singular or not finite");
      return v * (1 / n);
    };
    f.forward = unit(world.point({0, 0, -1}) - f.origin);
    f.up = unit(world.point({0, 1, 0}) - f.origin);
    return f;
  }

  void addCamera(size_t i, const Affine& world, const std::string& nodeName) {
    const json* cameras = array("cameras");
    const std::string where = "cameras[" + std::to_string(i) + "]";
    if (!cameras || i >= cameras->size()) fail(where + " does not exist");
    const json& c = (*cameras)[i];
    if (!c.is_object()) fail(where + " is not an object");
    FileCamera cam;
    cam.name = c.contains("name") && c["name"].is_string() ? c["name"].get<std::string>()
               : !nodeName.empty()                         ? nodeName
                                   : "camera " + std::to_string(info_.cameras.size());
    const Frame f = frameOf(world, where);
    cam.eye = f.origin;
    cam.lookAt = f.origin + f.forward;
    cam.up = f.up;
    const std::string type =
        c.contains("type") && c["type"].is_string() ? c["type"].get<std::string>() : "";
    cam.orthographic = type == "orthographic";
    if (type != "perspective" && type != "orthographic")
      fail(where + ".type must be \"perspective\" or \"orthographic\"");
    const auto p = c.find(type);
    if (p == c.end() || !p->is_object()) fail(where + " has no \"" + type + "\" parameters");
    if (cam.orthographic) {
      // Both required by glTF 2.0; a negative one would mirror the view.
      cam.xmag = number(*p, "xmag", 0, where + "." + type);
      if (!(cam.xmag > 0)) fail(where + ".orthographic.xmag must be positive");
      cam.ymag = number(*p, "ymag", 0, where + "." + type);
      if (!(cam.ymag > 0)) fail(where + ".orthographic.ymag must be positive");
      cam.aspectRatio = cam.xmag / cam.ymag;
    } else {
      const double yfov = number(*p, "yfov", 0, where + "." + type);
      if (!(yfov > 0 && yfov < M_PI)) fail(where + ".perspective.yfov must be in (0, π) radians");
      cam.yfovDegrees = yfov * 180 / M_PI;
      cam.aspectRatio = number(*p, "aspectRatio", 0, where + "." + type);
      if (cam.aspectRatio < 0) fail(where + ".perspective.aspectRatio must be positive");
    }
    info_.cameras.push_back(cam);
  }

  // Two nodes may place one camera, or name theirs alike: each camera is then chosen (--camera)
  // by a name of its own, the first by the shared name, the others by it and their node
  // ("Camera (nodes[4])", then "Camera (nodes[4] #2)" for a node reached again through shared
  // parents: each name is tried from the last number given, so a million copies take linear
  // time).
  void nameCamerasApart() {
    std::unordered_set<std::string> taken;
    std::unordered_map<std::string, int> copies;  // by "Camera (nodes[4]"
    for (size_t k = 0; k < info_.cameras.size(); ++k) {
      std::string& name = info_.cameras[k].name;
      if (taken.count(name)) {
        const std::string atNode = name + " (" + cameraNodes_[k];
        name = atNode + ")";
        for (int& n = copies[atNode]; taken.count(name);)
          name = atNode + " #" + std::to_string(++n + 1) + ")";
      }
      taken.insert(name);
    }
  }

  void addLight(size_t i, const Affine& world, const std::string& nodeName) {
    const auto ext = doc_.find("extensions");
    const json* lights = nullptr;
    if (ext != doc_.end() && ext->is_object())
      if (const auto k = ext->find("KHR_lights_punctual"); k != ext->end() && k->is_object())
        if (const auto l = k->find("lights"); l != k->end() && l->is_array()) lights = &*l;
    const std::string where = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
    if (!lights || i >= lights->size()) fail(where + " does not exist");
    const json& l = (*lights)[i];
    if (!l.is_object()) fail(where + " is not an object");
    FileLight light;
    light.name =
        l.contains("name") && l["name"].is_string() ? l["name"].get<std::string>() : nodeName;
    const std::string type =
        l.contains("type") && l["type"].is_string() ? l["type"].get<std::string>() : "";
    if (type == "directional")
      light.type = FileLight::Type::Directional;
    else if (type == "point")
      light.type = FileLight::Type::Point;
    else if (type == "spot") {
      light.type = FileLight::Type::Spot;
      // spot.innerConeAngle, outerConeAngle: 0 ≤ inner < outer ≤ π/2 (the specification).
      const auto spot = l.find("spot");
      if (spot != l.end() && !spot->is_object()) fail(where + ".spot is not an object");
      if (spot != l.end()) {
        light.innerConeAngle = number(*spot, "innerConeAngle", 0, where + ".spot");
        light.outerConeAngle = number(*spot, "outerConeAngle", M_PI / 4, where + ".spot");
      }
      if (!(light.innerConeAngle >= 0 && light.innerConeAngle < light.outerConeAngle &&
            light.outerConeAngle <= M_PI / 2))
        fail(where + ".spot must have 0 <= innerConeAngle < outerConeAngle <= pi/2");
    } else
      fail(where + ".type must be \"directional\", \"point\" or \"spot\"");
    if (const auto c = numbers(l, "color", 3, where); !c.empty()) {
      if (c[0] < 0 || c[1] < 0 || c[2] < 0) fail(where + ".color must not be negative");
      light.color = {float(c[0]), float(c[1]), float(c[2])};
    }
    light.intensity = number(l, "intensity", 1, where);
    if (light.intensity < 0) fail(where + ".intensity must not be negative");
    const Frame f = frameOf(world, where);
    light.position = f.origin;
    light.direction = f.forward;
    info_.lights.push_back(light);
  }

  std::string path_;
  json doc_;
  FileSceneInfo info_;
  std::vector<std::string> cameraNodes_;  // "nodes[i]" of each of info_.cameras
};

}  // namespace

FileSceneInfo readGltfSceneInfo(const std::string& path) {
  // The same check as every mesh file's: a FIFO named .gltf blocked here, /dev/zero was read
  // until memory ran out.
  checkInputFile(path, kMaxMeshFileBytes, "glTF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError("cannot open glTF file " + path + ": " + std::strerror(errno));
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  if (in.bad()) throw GlintError("cannot read glTF file " + path);
  // The same checks as the mesh reader's (nesting depth, glTF 2, strict JSON), on the same text;
  // what the file holds that Glint leaves out is said once, when the mesh reader takes it.
  const std::string text = lowerExtension(path) == ".glb" ? glbJsonChunk(path, bytes) : bytes;
  return Reader(path, parseGltfDocument(path, text)).read();
}

}  // namespace glint
