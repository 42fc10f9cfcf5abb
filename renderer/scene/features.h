#pragma once
// What a scene uses, computed once when it is loaded. Everything a scene does not use is left
// out at run time: no lens or time samples without a lens or motion, one shadow ray and no
// sample set for a delta light, no interior list outside dielectrics, no refraction rays
// without them, no AOV records unless asked for; `glint render --stats` lists both sides. (No
// capability is compiled out: specialised kernels saved too little to pay for keeping several,
// docs/performance.md, "Leaving out what a scene does not need".)
#include <cstdint>
#include <string>
#include <vector>

namespace glint {

struct Features {
  bool instancing = false;
  bool planes = false;
  bool pointLights = false;
  bool directionalLights = false;
  bool areaLights = false;
  bool environment = false;  // an environment light: misses see it, and it lights surfaces
  bool depthOfField = false;
  bool motion = false;  // some object has keys (time steps for Embree, a time sample)
  bool gloss = false;   // glossy reflection or blurred translucency
  bool shadows = false;
  bool specular = false;    // some Phong material has ks ≠ 0
  bool reflection = false;  // some material has km ≠ 0
  bool refraction = false;  // some dielectric
  bool absorption = false;  // some dielectric with attenuation ≠ 1
  bool textures = false;    // some colour slot is not a constant
  // Some image texture: hits compute their (u, v) and tangents (ShadingPoint::uv), and rays
  // carry the width of their pixel's footprint to filter the image over.
  bool surfaceCoordinates = false;
  // Some image texture reads a mesh's second coordinate set (ShadingPoint::uv1).
  bool secondUvSet = false;
  // Per material id, whether its surface reads texture coordinates (an image texture, a
  // normal, bump, metallic-roughness or occlusion map): only its hits compute them
  // (readsCoordinates), since finding them costs more than shading an untextured hit.
  std::vector<bool> coordinatesByMaterial;
  bool vertexColors = false;  // some slot multiplies by a mesh's vertex colours
  // Some material has a normal or bump map: hits compute their surface coordinates and tangent
  // frame (ShadingPoint::tangent), and meshes under a normal map carry vertex tangents.
  bool normalMaps = false;
  // Some material has an opacity cut-out: backends test candidate hits against it
  // (Scene::cutAway), and Embree gets filter functions for those geometries only.
  bool cutouts = false;
  bool emission = false;  // some surface emits (k_e, or a visible area light)
  bool ambient = false;
  bool transparentShadows = false;  // asked for and some dielectric can cast them

  // Whether hits on material `id` need their surface coordinates: yes for one not listed.
  bool readsCoordinates(uint32_t id) const {
    return id >= coordinatesByMaterial.size() || coordinatesByMaterial[id];
  }

  std::vector<std::string> used() const;
  std::vector<std::string> leftOut() const;
};

class Scene;
Features computeFeatures(const Scene& scene);

}  // namespace glint
