#pragma once
// Materials are a closed set, visited in one place (integrator/whitted.cpp). Every key of
// SCENE_FORMAT.md is kept here even where the integrator does not use it yet.
#include <cstdint>
#include <string>
#include <variant>

#include "core/affine.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

// A colour that is either constant or a procedural 3D checker (seed 001 §9 item 9).
struct ColorTexture {
  Rgb constant;
  bool checker = false;
  Rgb a, b;
  float scale = 1;

  // At a render-space point: the checker is fixed in world space, so the point is moved back
  // by the scene's worldOrigin (in double) before the cells are counted.
  Rgb eval(const Vec3f& renderP, const Vec3d& worldOrigin) const {
    return checker ? checkerAt(renderP, worldOrigin) : constant;
  }
  bool isBlack() const { return checker ? a.isBlack() && b.isBlack() : constant.isBlack(); }

 private:
  Rgb checkerAt(const Vec3f& renderP, const Vec3d& worldOrigin) const;
};

enum class SpecularModel { BlinnPhong, Phong };
enum class FresnelModel { Exact, Schlick };

struct PhongMaterial {
  ColorTexture ka, kd;
  // ka is kd (the scene gave no "ka"): the ambient term reuses the diffuse colour already
  // looked up at the shading point instead of evaluating the same texture twice.
  bool ambientFollowsDiffuse = false;
  Rgb ks, km;
  float exponent = 32;
  SpecularModel specularModel = SpecularModel::BlinnPhong;
  float gloss = 0;
};

struct MirrorMaterial {
  Rgb km{1, 1, 1};
  float gloss = 0;
};

struct DielectricMaterial {
  float ior = 1.5f;
  Rgb attenuation{1, 1, 1};  // fraction kept per unit distance inside (Beer)
  FresnelModel fresnel = FresnelModel::Exact;
  float blur = 0;
};

using Material = std::variant<PhongMaterial, MirrorMaterial, DielectricMaterial>;

struct NamedMaterial {
  std::string name;
  Material material;
};

}  // namespace glint
