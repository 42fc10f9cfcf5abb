#include "scene/features.h"

#include <utility>

#include "scene/scene.h"

namespace glint {

namespace {
std::vector<std::pair<const char*, bool>> table(const Features& f) {
  return {{"instancing", f.instancing},
          {"planes", f.planes},
          {"point_lights", f.pointLights},
          {"directional_lights", f.directionalLights},
          {"area_lights", f.areaLights},
          {"environment_light", f.environment},
          {"motion_blur", f.motion},
          {"depth_of_field", f.depthOfField},
          {"gloss", f.gloss},
          {"shadows", f.shadows},
          {"specular", f.specular},
          {"reflection", f.reflection},
          {"refraction", f.refraction},
          {"absorption", f.absorption},
          {"textures", f.textures},
          {"image_textures", f.surfaceCoordinates},
          {"second_uv_set", f.secondUvSet},
          {"vertex_colors", f.vertexColors},
          {"normal_bump_maps", f.normalMaps},
          {"opacity_cutouts", f.cutouts},
          {"emission", f.emission},
          {"ambient", f.ambient},
          {"transparent_shadows", f.transparentShadows}};
}
std::vector<std::string> pick(const Features& f, bool want) {
  std::vector<std::string> out;
  for (auto& [name, on] : table(f))
    if (on == want) out.emplace_back(name);
  return out;
}
}  // namespace

std::vector<std::string> Features::used() const { return pick(*this, true); }
std::vector<std::string> Features::leftOut() const { return pick(*this, false); }

Features computeFeatures(const Scene& scene) {
  Features f;
  f.instancing = !scene.instances.empty();
  f.planes = !scene.planes.empty();
  for (const auto& l : scene.lights) {
    if (std::holds_alternative<PointLight>(l)) f.pointLights = true;
    if (std::holds_alternative<DirectionalLight>(l)) f.directionalLights = true;
    if (std::holds_alternative<QuadLight>(l) || std::holds_alternative<DiskLight>(l))
      f.areaLights = true;
    if (std::holds_alternative<EnvironmentLight>(l)) f.environment = true;
  }
  f.shadows = !scene.lights.empty();
  f.ambient = !scene.render.ambient.isBlack();
  f.depthOfField = scene.cameraDesc.apertureRadius > 0;
  for (const auto& keys : scene.sphereCenterKeys) f.motion |= !keys.empty();
  for (const auto& m : scene.meshes) f.motion |= m.deforming();
  for (const auto& inst : scene.instances) f.motion |= !inst.motion.empty();
  for (const Material& m : scene.materials) {
    const Surface& s = m.surface;
    f.specular |= !s.ks.isBlack();
    f.reflection |= s.reflectsCoherently();
    f.gloss |= s.reflectsCoherently() && s.glossy();
    f.emission |= s.emits();
    f.cutouts |= m.cutout.active();
    bool coordinates = false;
    if (s.normalMaps) {
      f.normalMaps = coordinates = true;
      f.secondUvSet |=
          s.normalMaps->normal.uvTransform.uvSet == 1 || s.normalMaps->bump.uvTransform.uvSet == 1;
    }
    for (const ColorTexture* t : {&s.ka, &s.kd, &s.ks, &s.km, &s.ke}) {
      f.textures |= t->pattern != TexturePattern::Constant;
      coordinates |= t->pattern == TexturePattern::Image;
      f.secondUvSet |= t->pattern == TexturePattern::Image && t->uvTransform.uvSet == 1;
      f.vertexColors |= t->pattern == TexturePattern::VertexColor || t->timesVertexColor;
    }
    if (s.maps) {
      for (const auto& [image, uv] :
           {std::pair{s.maps->metallicRoughness.get(), &s.maps->metallicRoughnessUv},
            std::pair{s.maps->occlusion.get(), &s.maps->occlusionUv}})
        if (image) {
          f.textures = coordinates = true;
          f.secondUvSet |= uv->uvSet == 1;
        }
    }
    f.coordinatesByMaterial.push_back(coordinates);
    f.surfaceCoordinates |= coordinates;
    if (m.refracts()) {
      f.refraction = f.reflection = true;
      f.absorption |= m.dielectric.absorption.absorbs();
      f.gloss |= m.dielectric.blurs();
    }
  }
  f.surfaceCoordinates |= f.normalMaps;
  f.transparentShadows = scene.render.transparentShadows && f.refraction && f.shadows;
  return f;
}

}  // namespace glint
