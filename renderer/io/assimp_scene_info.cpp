#include "io/assimp_scene_info.h"

#include <assimp/scene.h>

#include <array>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/log.h"

namespace glint {

namespace {

// Assimp's own steps recurse through the node tree; so does Glint's mesh placement, to the same
// depth (io/mesh_io.cpp).
constexpr int kMaxNodeDepth = 1024;

// Every named node's world transform (a 3 × 4 affine, rows), in double: the first node of a
// name wins, as Assimp's FindNode has it.
void collectNodes(const aiNode& node, const Affine& parent, int depth,
                  std::map<std::string, Affine>& out) {
  const aiMatrix4x4& l = node.mTransformation;
  const Affine world = parent * Affine::fromRows({l.a1, l.a2, l.a3, l.a4, l.b1, l.b2, l.b3, l.b4,
                                                  l.c1, l.c2, l.c3, l.c4});
  out.emplace(node.mName.C_Str(), world);
  for (unsigned c = 0; c < node.mNumChildren && depth < kMaxNodeDepth; ++c)
    if (node.mChildren[c]) collectNodes(*node.mChildren[c], world, depth + 1, out);
}

class Placer {
 public:
  Placer(const aiScene& s, std::string path) : path_(std::move(path)) {
    if (s.mRootNode) collectNodes(*s.mRootNode, Affine{}, 0, nodes_);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw UsageError("mesh " + path_ + ": " + what);
  }

  const Affine& node(const aiString& name, const std::string& what) const {
    const auto it = nodes_.find(name.C_Str());
    if (it == nodes_.end()) fail(what + " has no node of its name to place it");
    return it->second;
  }

  Vec3d point(const Affine& world, const aiVector3D& p, const std::string& what) const {
    const Vec3d v = world.point({p.x, p.y, p.z});
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      fail(what + " is placed at a non-finite position");
    return v;
  }

  // A direction of the node's frame in world space, unit length.
  Vec3d direction(const Affine& world, const aiVector3D& d, const std::string& what) const {
    const Vec3d v = world.point({d.x, d.y, d.z}) - world.point({0, 0, 0});
    const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(n > 0) || !std::isfinite(n))
      fail(what + "'s direction is zero or not finite once placed by its node");
    return v * (1 / n);
  }

 private:
  std::string path_;
  std::map<std::string, Affine> nodes_;
};

FileCamera camera(const aiCamera& c, const Placer& place) {
  FileCamera cam;
  cam.name = c.mName.C_Str();
  const std::string what = "camera " + inQuotes(excerpt(cam.name));
  const Affine& world = place.node(c.mName, what);
  cam.eye = place.point(world, c.mPosition, what);
  cam.lookAt = cam.eye + place.direction(world, c.mLookAt, what);
  cam.up = place.direction(world, c.mUp, what);
  cam.aspectRatio = std::isfinite(c.mAspect) && c.mAspect > 0 ? c.mAspect : 0;
  if (std::isfinite(c.mOrthographicWidth) && c.mOrthographicWidth > 0) {
    // Half the view's width (aiCamera); the height follows the aspect, else the width.
    cam.orthographic = true;
    cam.xmag = c.mOrthographicWidth;
    cam.ymag = cam.aspectRatio > 0 ? cam.xmag / cam.aspectRatio : cam.xmag;
    cam.aspectRatio = cam.xmag / cam.ymag;
    return cam;
  }
  if (!(c.mHorizontalFOV > 0 && c.mHorizontalFOV < M_PI))
    place.fail(what + "'s horizontal field of view " + std::to_string(c.mHorizontalFOV) +
               " rad is not in (0, π)");
  if (cam.aspectRatio > 0)
    cam.yfovDegrees =
        2 * std::atan(std::tan(0.5 * c.mHorizontalFOV) / cam.aspectRatio) * 180 / M_PI;
  else
    cam.xfovDegrees = c.mHorizontalFOV * 180 / M_PI;
  return cam;
}

// Assimp's attenuation 1 / (c + l·d + q·d²) as Glint's falloffs: none (scaled by 1/c) or 1/r²
// (scaled by 1/q); a linear term, or a constant beside a quadratic one, has no match.
void attenuation(const aiLight& l, FileLight& light, const std::string& where) {
  const float c = l.mAttenuationConstant, lin = l.mAttenuationLinear, q = l.mAttenuationQuadratic;
  const auto positive = [](float v) { return std::isfinite(v) && v > 0; };
  light.inverseSquare = positive(q);
  light.intensity = positive(q) ? 1 / double(q) : positive(c) ? 1 / double(c) : 1;
  if (positive(lin) || (positive(q) && positive(c)))
    log::warning(where + ": attenuation (constant " + std::to_string(c) + ", linear " +
                 std::to_string(lin) + ", quadratic " + std::to_string(q) + ") rendered as " +
                 (light.inverseSquare ? "quadratic alone (1/r²)" : "constant (no falloff)") +
                 "; Glint's lights fall off with 1/r² or not at all");
}

}  // namespace

FileSceneInfo sceneInfoFromAssimp(const aiScene& s, const std::string& path) {
  const Placer place(s, path);
  FileSceneInfo info;
  for (unsigned i = 0; i < s.mNumCameras; ++i)
    if (s.mCameras[i]) info.cameras.push_back(camera(*s.mCameras[i], place));
  for (unsigned i = 0; i < s.mNumLights; ++i) {
    if (!s.mLights[i]) continue;
    const aiLight& l = *s.mLights[i];
    FileLight light;
    light.name = l.mName.C_Str();
    const std::string what = "light " + inQuotes(excerpt(light.name));
    light.photometric = false;
    if (l.mType == aiLightSource_DIRECTIONAL)
      light.type = FileLight::Type::Directional;
    else if (l.mType == aiLightSource_POINT)
      light.type = FileLight::Type::Point;
    else if (l.mType == aiLightSource_SPOT)
      light.type = FileLight::Type::Spot;
    else {
      log::warning("mesh " + path + ": " + what + " left out: Glint renders " +
                   "directional, point and spot lights from mesh files, not " +
                   (l.mType == aiLightSource_AMBIENT ? "ambient"
                    : l.mType == aiLightSource_AREA  ? "area"
                                                     : "undefined") +
                   " ones");
      continue;
    }
    const aiColor3D& c = l.mColorDiffuse;
    if (!(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && c.r >= 0 && c.g >= 0 &&
          c.b >= 0))
      place.fail(what + "'s colour is negative or not finite");
    light.color = {c.r, c.g, c.b};
    const Affine& world = place.node(l.mName, what);
    if (light.type != FileLight::Type::Directional) {
      light.position = place.point(world, l.mPosition, what);
      attenuation(l, light, "mesh " + path + ": " + what);
    }
    if (light.type != FileLight::Type::Point)
      light.direction = place.direction(world, l.mDirection, what);
    if (light.type == FileLight::Type::Spot) {
      // Assimp's cone angles are whole angles (aiLight), Glint's from the axis, within 90°.
      const auto half = [](float a) {
        return std::isfinite(a) && a > 0 ? std::min(0.5 * a, M_PI / 2) : M_PI / 2;
      };
      light.outerConeAngle = half(l.mAngleOuterCone);
      light.innerConeAngle = std::min(half(l.mAngleInnerCone), light.outerConeAngle);
    }
    info.lights.push_back(light);
  }
  return info;
}

}  // namespace glint
