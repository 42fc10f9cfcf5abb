#include "materials/material.h"

namespace glint {

Material defaultMaterial(MaterialKind kind) {
  Material m;
  m.kind = kind;
  Surface& s = m.surface;
  if (kind == MaterialKind::Phong) s.kd = ColorTexture::uniform({0.5f, 0.5f, 0.5f});
  if (kind == MaterialKind::Mirror) s.km = ColorTexture::uniform({1, 1, 1});
  s.ka = s.kd;  // every kind: k_a follows k_d unless the scene gives it
  s.ambientFollowsDiffuse = true;
  return m;
}

Rgb albedo(const Material& m, const SurfacePoint& at) {
  if (m.refracts()) return {1, 1, 1};
  return at.kd.isBlack() ? at.km : at.kd;
}

}  // namespace glint
