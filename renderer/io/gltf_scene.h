#pragma once
// What a glTF 2.0 file says about its scene beyond the meshes (which Assimp places,
// io/mesh_io.h): its cameras and its KHR_lights_punctual lights, each placed by the node tree
// of the file's default scene (every node's transform composed with its parents').
#include <cmath>
#include <string>
#include <vector>

#include "core/affine.h"
#include "core/rgb.h"

namespace glint {

struct GltfCamera {
  std::string name;       // the camera's name, else its node's, else "camera N"
  Vec3d eye, lookAt, up;  // world space: glTF cameras look down their node's −z, +y up
  bool orthographic = false;
  double yfovDegrees = 40;    // perspective
  double xmag = 1, ymag = 1;  // orthographic: half the view's width and height
  // Width / height, 0 when the file does not say; an orthographic camera's is xmag / ymag.
  double aspectRatio = 0;
};

struct GltfLight {
  enum class Type { Directional, Point, Spot };
  Type type = Type::Point;
  std::string name;
  Rgb color{1, 1, 1};
  double intensity = 1;  // candela (point, spot) or lux (directional)
  Vec3d position;        // point, spot
  Vec3d direction;       // directional, spot: unit, the way the light travels (node's −z)
  double innerConeAngle = 0, outerConeAngle = M_PI / 4;  // spot: radians from the axis
};

struct GltfSceneInfo {
  std::vector<GltfCamera> cameras;
  std::vector<GltfLight> lights;
};

// Reads the cameras and lights of the .gltf or .glb file `path`. Throws UsageError naming the
// file and the node, camera or light that is wrong (a node that is its own ancestor, an index
// out of range, a non-finite or singular transform, a camera without its parameters).
GltfSceneInfo readGltfSceneInfo(const std::string& path);

}  // namespace glint
