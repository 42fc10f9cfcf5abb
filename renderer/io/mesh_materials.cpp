#include "io/mesh_materials.h"

#include <assimp/GltfMaterial.h>
#include <assimp/ObjMaterial.h>
#include <assimp/material.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "io/json_source.h"

namespace glint {

namespace {

std::string colourText(const Rgb& c) {
  return "(" + formatNumber(c.r) + ", " + formatNumber(c.g) + ", " + formatNumber(c.b) + ")";
}

// A mesh file material's values, each as the file writes it where Glint can use it; where it
// cannot (not finite, a negative channel, outside its range) a warning names the material, the
// value and what is used instead: a file's value is never replaced silently.
struct MaterialValues {
  const aiMaterial& src;
  const std::string& material;  // "FILE:NAME"

  void warn(const char* label, const std::string& problem, const std::string& used) const {
    log::warning("material " + material + ": " + label + " " + problem + ": " + used + " is used");
  }
  // A colour, or `otherwise` where the file has none.
  Rgb colour(const char* label, const char* key, unsigned type, unsigned index,
             Rgb otherwise) const {
    aiColor4D c;
    if (src.Get(key, type, index, c) != AI_SUCCESS) return otherwise;
    const Rgb read{c.r, c.g, c.b};
    if (!read.isFinite()) {
      warn(label, colourText(read) + " is not finite", colourText(otherwise));
      return otherwise;
    }
    const Rgb used{std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
    if (!(used == read))
      warn(label, colourText(read) + " has a negative channel", colourText(used));
    return used;
  }
  // What a number outside its range becomes: the nearest end, or the value of a file without it.
  enum class Outside { Clamped, Default };
  // A number, or `otherwise` where the file has none. One in [quietFrom, lo) is raised to lo
  // without a warning (a convention of the format, not a fault of the file).
  float number(const char* label, const char* key, unsigned type, unsigned index, float otherwise,
               float lo = -INFINITY, float hi = INFINITY, Outside outside = Outside::Clamped,
               float quietFrom = INFINITY) const {
    float v = 0;
    if (src.Get(key, type, index, v) != AI_SUCCESS) return otherwise;
    if (!std::isfinite(v)) {
      warn(label, formatNumber(v) + " is not finite", formatNumber(otherwise));
      return otherwise;
    }
    const float used =
        outside == Outside::Default && !(v >= lo && v <= hi) ? otherwise : std::clamp(v, lo, hi);
    if (used != v && !(v >= quietFrom && v < lo))
      warn(label,
           formatNumber(v) + " is outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "]",
           formatNumber(used));
    return used;
  }
};

// The material's first texture of `type`, where it has one that opens.
std::shared_ptr<const ImageTexture> firstTexture(const aiMaterial& m, aiTextureType type,
                                                 const TextureOpener& open) {
  aiString path;
  if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &path) != AI_SUCCESS) return nullptr;
  return open(path.C_Str());
}

// The slot's colour `factor` times the material's first texture of `type`, read through
// `uvTransform`, where it has one that opens; else the factor alone.
ColorTexture textured(const aiMaterial& m, aiTextureType type, const Rgb& factor,
                      const TextureOpener& open, const UvTransform& uvTransform = {}) {
  ColorTexture t = ColorTexture::uniform(factor);
  if (auto image = firstTexture(m, type, open)) {
    t.pattern = TexturePattern::Image;
    t.image = std::move(image);
    t.uvTransform = uvTransform;
  }
  return t;
}

// MTL's dissolve (another format's opacity, `obj` false): map_d (its alpha, else its grey)
// times d makes a cut-out at one half. A dissolve without a map would blend the surface with
// what is behind it, which Glint does not render (materials/cutout.h): the surface stays
// opaque, with a warning (not for glass, whose dissolve exporters write for the transparency
// Glint renders by refraction).
Cutout mtlCutout(const MaterialValues& v, const TextureOpener& open, const Material& m, bool obj) {
  Cutout c;
  const float d = v.number(obj ? "dissolve (d)" : "opacity", AI_MATKEY_OPACITY, 1.0f, 0.0f, 1.0f);
  c.image = firstTexture(v.src, aiTextureType_OPACITY, open);
  if (c.image) {
    c.coverage = d;
    c.channel = Cutout::Channel::AlphaElseGrey;
  } else if (d < 1 && !m.refracts()) {
    log::warning("material " + m.name + ": " + (obj ? "dissolve d " : "opacity ") +
                 std::to_string(d) + (obj ? " without map_d" : " without an opacity texture") +
                 " is not rendered (Glint cuts out, it does not blend): opaque");
  }
  return c;
}

// glTF's alphaMode: "MASK" cuts where the base colour's alpha (factor times texture, read
// through `baseColorUv`) is below alphaCutoff; "BLEND" would blend, which Glint does not render:
// opaque, with a warning.
Cutout gltfCutout(const MaterialValues& v, const TextureOpener& open,
                  const UvTransform& baseColorUv) {
  const aiMaterial& src = v.src;
  const std::string& name = v.material;
  Cutout c;
  aiString mode;
  if (src.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) != AI_SUCCESS) return c;
  const std::string alphaMode = mode.C_Str();
  if (alphaMode == "BLEND")
    log::warning("material " + name +
                 ": alphaMode BLEND is not rendered (Glint cuts out, it does not blend): opaque");
  else if (alphaMode != "OPAQUE" && alphaMode != "MASK")
    log::warning("material " + name + ": alphaMode " + inQuotes(alphaMode) +
                 " is not one glTF defines (OPAQUE, MASK, BLEND): opaque");
  if (alphaMode != "MASK") return c;
  aiColor4D base(1, 1, 1, 1);
  src.Get(AI_MATKEY_BASE_COLOR, base);
  c.coverage = std::isfinite(base.a) ? std::clamp(base.a, 0.0f, 1.0f) : 1.0f;
  c.cutoff = v.number("alphaCutoff", AI_MATKEY_GLTF_ALPHACUTOFF, 0.5f, 0.0f, 1.0f);
  c.image = firstTexture(src, aiTextureType_DIFFUSE, open);
  if (c.image) c.uvTransform = baseColorUv;
  c.channel = Cutout::Channel::Alpha;
  return c;
}

// The normal and bump maps of a mesh file's material: glTF's normalTexture (Assimp's NORMALS)
// with its scale and transform; MTL's norm (NORMALS) and bump / map_Bump (HEIGHT), each with its
// -bm multiplier as the scale (a height map's in the mesh's units), and the other formats'
// NORMALS and HEIGHT textures alike (scale 1). Null where it has neither (or they do not open).
std::shared_ptr<const ShadingMaps> shadingMaps(const MaterialValues& v, MeshFileFormat format,
                                               const TextureOpener& open,
                                               const GltfMaterialInfo& gltf) {
  const aiMaterial& src = v.src;
  auto maps = std::make_shared<ShadingMaps>();
  maps->normal.image = firstTexture(src, aiTextureType_NORMALS, open);
  if (format == MeshFileFormat::Gltf) {
    maps->normal.scale = gltf.normalScale;
    maps->normal.uvTransform = gltf.normalUv;
  } else {
    maps->normal.scale = v.number("normal map's -bm", AI_MATKEY_OBJ_BUMPMULT_NORMALS(0), 1.0f);
    maps->bump.image = firstTexture(src, aiTextureType_HEIGHT, open);
    maps->bump.scale = v.number("bump map's -bm", AI_MATKEY_OBJ_BUMPMULT_HEIGHT(0), 1.0f);
  }
  if (!maps->normal.image && !maps->bump.image) return nullptr;
  return maps;
}

// MTL's illumination models (the OBJ specification's `illum`): 3, 5 and 8 trace reflections,
// whose colour is Ks; 4, 6, 7 and 9 are glass, refracting with index Ni.
bool illumReflects(int illum) { return illum == 3 || illum == 5 || illum == 8; }
bool illumRefracts(int illum) { return illum == 4 || illum == 6 || illum == 7 || illum == 9; }

// An OBJ's MTL, or another format's common keys (`format` Other). MTL's map_Kd multiplies Kd
// (the OBJ specification); in Collada a <diffuse> holds a colour or a texture, and an FBX or 3DS
// texture takes the colour's place while the file keeps the colour its tool last showed (a
// grey): there the texture replaces the colour.
Material fromMtl(const MaterialValues& v, const TextureOpener& open, MeshFileFormat format) {
  const aiMaterial& src = v.src;
  int illum = 2;
  if (format == MeshFileFormat::Obj) src.Get(AI_MATKEY_OBJ_ILLUM, illum);
  Material m =
      defaultMaterial(illumRefracts(illum) ? MaterialKind::Dielectric : MaterialKind::Phong);
  Surface& s = m.surface;
  const Rgb ks = v.colour("specular colour (Ks)", AI_MATKEY_COLOR_SPECULAR, {0, 0, 0});
  // Glass takes its colour from the light it refracts, not from a diffuse Kd.
  const bool mapReplacesColour =
      format != MeshFileFormat::Obj && src.GetTextureCount(aiTextureType_DIFFUSE) > 0;
  if (!m.refracts())
    s.kd = textured(src, aiTextureType_DIFFUSE,
                    mapReplacesColour ? Rgb{1, 1, 1}
                                      : v.colour("diffuse colour (Kd)", AI_MATKEY_COLOR_DIFFUSE,
                                                 {0.5f, 0.5f, 0.5f}),
                    open);
  s.ka = ColorTexture::uniform(v.colour("ambient colour (Ka)", AI_MATKEY_COLOR_AMBIENT, {0, 0, 0}));
  s.ambientFollowsDiffuse = false;
  // The highlight's strength scales its colour (an FBX's SpecularFactor: Blender writes a
  // specular colour of 0.8 beside a factor of 0 for a matte surface). MTL has none.
  const float strength = v.number("specular strength (shininess strength)",
                                  AI_MATKEY_SHININESS_STRENGTH, 1.0f, 0.0f, 1e4f);
  s.ks = textured(src, aiTextureType_SPECULAR, ks * strength, open);
  // Ns is the Phong exponent (0 … 1000 in the specification); Glint's must be at least 1, which
  // Ns in [0, 1) (Ns 0 is common in exported files) takes without a word.
  s.exponent = v.number("shininess (Ns)", AI_MATKEY_SHININESS, 32, 1.0f, 1e4f,
                        MaterialValues::Outside::Clamped, 0.0f);
  // map_Ke scales Ke; exporters write Ke 0 beside an emission map, which then means 1.
  const Rgb ke = v.colour("emissive colour (Ke)", AI_MATKEY_COLOR_EMISSIVE, {0, 0, 0});
  const bool keMap = src.GetTextureCount(aiTextureType_EMISSIVE) > 0;
  s.ke = textured(src, aiTextureType_EMISSIVE, keMap && ke.isBlack() ? Rgb{1, 1, 1} : ke, open);
  if (illumReflects(illum)) s.km = ColorTexture::uniform(ks);
  if (m.refracts()) {
    // Plain glass where Ni is absent or outside what Glint refracts with.
    m.dielectric.ior = v.number("index of refraction (Ni)", AI_MATKEY_REFRACTI, 1.5f, 1.0f, 10.0f,
                                MaterialValues::Outside::Default);
  }
  return m;
}

// glTF's metallic-roughness model on the general surface: the dielectric base reflects diffusely
// (k_d = base × (1 − metallic)) with a 4 % highlight; the metal part mirrors its base colour
// (k_m = base × metallic), blurred by its roughness (gloss); the highlight's exponent is
// Blinn-Phong's match to the GGX width α = roughness² (materials/surface_maps.h). A
// metallic-roughness texture makes that split per texel (the surface's maps); an occlusion
// texture darkens the ambient term, which is the diffuse colour's. The textures are read through
// their KHR_texture_transform, texCoord and sampler, which Glint reads itself (`own`).
Material fromGltf(const MaterialValues& v, const TextureOpener& open, const GltfMaterialInfo& own) {
  const aiMaterial& src = v.src;
  const float transmission =
      v.number("transmissionFactor", AI_MATKEY_TRANSMISSION_FACTOR, 0.0f, 0.0f, 1.0f);
  Material m = defaultMaterial(transmission > 0 ? MaterialKind::Dielectric : MaterialKind::Phong);
  Surface& s = m.surface;
  const Rgb base = v.colour("baseColorFactor", AI_MATKEY_BASE_COLOR, {1, 1, 1});
  const float metallic = v.number("metallicFactor", AI_MATKEY_METALLIC_FACTOR, 1.0f, 0.0f, 1.0f);
  const float roughness = v.number("roughnessFactor", AI_MATKEY_ROUGHNESS_FACTOR, 1.0f, 0.0f, 1.0f);
  // Assimp's glTF 2 reader gives metallicRoughnessTexture as aiTextureType_UNKNOWN and
  // occlusionTexture as aiTextureType_LIGHTMAP.
  auto metallicRoughness = m.refracts() ? nullptr : firstTexture(src, aiTextureType_UNKNOWN, open);
  auto occlusion = firstTexture(src, aiTextureType_LIGHTMAP, open);
  // The base colour texture multiplies the base colour wherever it appears (baseColorTexture
  // is aiTextureType_DIFFUSE in Assimp's glTF 2 reader). With a metallic-roughness map, k_d and
  // k_s hold the base colour and the dielectric's highlight, which the map splits per texel.
  const float diffusePart = metallicRoughness ? 1 : 1 - metallic;
  if (!m.refracts())
    s.kd = textured(src, aiTextureType_DIFFUSE, base * diffusePart, open, own.baseColorUv);
  s.ka = s.kd;
  s.ambientFollowsDiffuse = true;
  s.ks = ColorTexture::uniform(metallicRoughness
                                   ? Rgb{0.04f, 0.04f, 0.04f}
                                   : Rgb{0.04f, 0.04f, 0.04f} * (1 - metallic) + base * metallic);
  s.exponent = blinnPhongExponent(roughness);
  s.km = metallic > 0 ? textured(src, aiTextureType_DIFFUSE, base * metallic, open, own.baseColorUv)
                      : ColorTexture::uniform({0, 0, 0});
  s.gloss = metallic > 0 ? roughness : 0;
  if (metallicRoughness || occlusion) {
    auto maps = std::make_shared<SurfaceMaps>();
    maps->metallicRoughness = std::move(metallicRoughness);
    maps->metallicRoughnessUv = own.metallicRoughnessUv;
    maps->metallicFactor = metallic;
    maps->roughnessFactor = roughness;
    maps->occlusion = std::move(occlusion);
    maps->occlusionUv = own.occlusionUv;
    maps->occlusionStrength = own.occlusionStrength;
    s.maps = std::move(maps);
  }
  s.ke = textured(
      src, aiTextureType_EMISSIVE,
      v.colour("emissiveFactor", AI_MATKEY_COLOR_EMISSIVE, {0, 0, 0}) * own.emissiveStrength, open,
      own.emissiveUv);
  if (m.refracts()) {
    m.dielectric.ior = v.number("ior (KHR_materials_ior)", AI_MATKEY_REFRACTI, 1.5f, 1.0f, 10.0f,
                                MaterialValues::Outside::Default);
    // KHR_materials_volume: light keeps attenuationColor after attenuationDistance, so a
    // fraction c^(1/D) per unit distance: Beer's law (seed 000 §13.1).
    const float distance = v.number("attenuationDistance (KHR_materials_volume)",
                                    AI_MATKEY_VOLUME_ATTENUATION_DISTANCE, INFINITY);
    const Rgb c = v.colour("attenuationColor (KHR_materials_volume)",
                           AI_MATKEY_VOLUME_ATTENUATION_COLOR, {1, 1, 1});
    if (distance > 0 && std::isfinite(distance)) {
      const auto perUnit = [&](float channel) {
        return std::pow(std::clamp(channel, 0.0f, 1.0f), 1 / distance);
      };
      m.dielectric.absorption = BeerMedium(Rgb{perUnit(c.r), perUnit(c.g), perUnit(c.b)});
    }
  }
  return m;
}

}  // namespace

void VertexColourChannels::warnIfReplaced(const std::string& mesh) const {
  if (replaced > 0)
    log::warning("mesh " + mesh + ": " + std::to_string(replaced) +
                 " vertex colour channels are negative or not finite: 0 is used");
}

void multiplyDiffuseByVertexColors(Surface& surface) {
  if (surface.kd.pattern == TexturePattern::Constant)
    surface.kd.pattern = TexturePattern::VertexColor;
  if (surface.kd.pattern == TexturePattern::Image) surface.kd.timesVertexColor = true;
  if (surface.ambientFollowsDiffuse) surface.ka = surface.kd;
}

Material materialFromMeshFile(const aiMaterial& source, MeshFileFormat format,
                              const std::string& fileName, const TextureOpener& openTexture,
                              const std::vector<GltfMaterialInfo>& gltfMaterials) {
  aiString name;
  std::string own = source.Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? name.C_Str() : "";
  // A glTF material reached Assimp named by its index in the file (io/gltf_subset.h): its own
  // name is restored as Assimp would have read it (an aiString: at most 1023 bytes, up to the
  // first NUL), and its texture transforms found.
  GltfMaterialInfo gltf;
  if (const auto i = gltfMaterialIndex(own);
      format == MeshFileFormat::Gltf && i && *i < gltfMaterials.size()) {
    gltf = gltfMaterials[*i];
    own = aiString(gltf.name).C_Str();
  }
  // A file without materials of its own (a PLY, an OBJ without MTL) gets Assimp's default,
  // which Glint replaces by its own default surface.
  const std::string named = fileName + ":" + own;
  const MaterialValues values{source, named};
  Material m = own == AI_DEFAULT_MATERIAL_NAME || format == MeshFileFormat::Ply
                   ? defaultMaterial(MaterialKind::Phong)
               : format == MeshFileFormat::Gltf ? fromGltf(values, openTexture, gltf)
                                                : fromMtl(values, openTexture, format);
  m.name = named;
  if (format != MeshFileFormat::Ply)
    m.surface.normalMaps = shadingMaps(values, format, openTexture, gltf);
  if (format == MeshFileFormat::Gltf) m.cutout = gltfCutout(values, openTexture, gltf.baseColorUv);
  if (format == MeshFileFormat::Obj || format == MeshFileFormat::Other)
    m.cutout = mtlCutout(values, openTexture, m, format == MeshFileFormat::Obj);
  return m;
}

}  // namespace glint
