#pragma once
// The cameras and lights a mesh file brings with it (a glTF file's, io/gltf_scene.h; a Collada,
// FBX, 3DS ... file's through Assimp, io/mesh_io.h), placed in world space by the file's node
// tree, in glTF's terms: a command given the file as its scene uses them in place of the
// default camera and light (app/scene_source.h).
#include <cmath>
#include <string>
#include <vector>

#include "core/affine.h"
#include "core/rgb.h"

namespace glint {

struct FileCamera {
  std::string name;       // the camera's name, else its node's, else "camera N"
  Vec3d eye, lookAt, up;  // world space
  bool orthographic = false;
  double yfovDegrees = 40;  // perspective
  // Perspective, where the file gives the horizontal angle without an aspect ratio: the
  // vertical angle follows from the image's aspect (0: yfovDegrees holds).
  double xfovDegrees = 0;
  double xmag = 1, ymag = 1;  // orthographic: half the view's width and height
  // Width / height, 0 when the file does not say; an orthographic camera's is xmag / ymag.
  double aspectRatio = 0;
};

struct FileLight {
  enum class Type { Directional, Point, Spot };
  Type type = Type::Point;
  std::string name;
  Rgb color{1, 1, 1};
  // Photometric (glTF): candela (point, spot) or lux (directional). Otherwise in Glint's units,
  // as Collada's and Assimp's other formats' lights are: a white diffuse surface facing the
  // light reflects colour × intensity (docs/shading.md).
  double intensity = 1;
  bool photometric = true;
  bool inverseSquare = true;  // point, spot: falls off with 1/r², else not at all
  Vec3d position;             // point, spot
  Vec3d direction;            // directional, spot: unit, the way the light travels (node's −z)
  double innerConeAngle = 0, outerConeAngle = M_PI / 4;  // spot: radians from the axis
};

struct FileSceneInfo {
  std::vector<FileCamera> cameras;
  std::vector<FileLight> lights;
};

}  // namespace glint
