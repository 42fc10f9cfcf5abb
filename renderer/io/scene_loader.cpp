#include "io/scene_loader.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/hash.h"
#include "core/input_files.h"
#include "core/json_memory.h"
#include "core/log.h"
#include "core/sampler.h"
#include "io/animation.h"
#include "io/object_names.h"
#include "io/scene_builder.h"
#include "io/texture_file.h"

namespace glint {

std::shared_ptr<const ImageTexture> SceneBuilder::texture(const std::string& path,
                                                          const std::string& colorspace) {
  auto& slot = textures[{path, colorspace}];
  if (slot) return slot;
  slot = openImageTexture(path, colorspace);
  // The file's bytes join the scene hash, as a mesh file's do: crops rendered after a texture
  // changed are not merged with ones rendered before.
  std::ifstream in(path, std::ios::binary);
  scene.sourceHash =
      hashCombine(scene.sourceHash, hashBytes(std::string(std::istreambuf_iterator<char>(in), {})));
  return slot;
}

std::string SceneBuilder::claimName(const JsonNode& n) {
  const std::string name = parseObjectName(n);
  const auto [it, added] =
      givenNames.emplace(name, n.path() + " (line " + std::to_string(n.loc().line) + ")");
  if (!added)
    n.fail(inQuotes(excerpt(name)) + " is already the name of " + it->second +
           "; names of objects and lights must be unique");
  return name;
}

namespace {

void parseRender(const JsonNode& n, RenderSettings& r) {
  n.checkKeys({"width", "height", "spp", "max_depth", "seed", "sampler", "background", "ambient",
               "transparent_shadows", "transparent_background"});
  if (auto v = n.get("width")) r.width = v->integer(1, 1 << 15);
  if (auto v = n.get("height")) r.height = v->integer(1, 1 << 15);
  if (auto v = n.get("spp")) r.spp = v->integer(1, static_cast<int>(kMaxSampleSet));
  if (auto v = n.get("max_depth")) r.maxDepth = v->integer(0, 1000);
  if (auto v = n.get("seed")) r.seed = v->unsignedInteger();
  if (auto v = n.get("sampler"))
    parseSamplerKind(v->choice({"regular", "random", "stratified", "sobol"}), r.sampler);
  r.background = n.color("background", r.background);
  r.ambient = n.color("ambient", r.ambient);
  if (auto v = n.get("transparent_shadows")) r.transparentShadows = v->boolean();
  if (auto v = n.get("transparent_background")) r.transparentBackground = v->boolean();
}

// A solid pattern: {"checker" | "noise" | "marble" | "wood": {"scale", "a", "b"}}.
ColorTexture parseSolidTexture(const JsonNode& n, TexturePattern pattern) {
  n.checkKeys({"scale", "a", "b"});
  ColorTexture t;
  t.pattern = pattern;
  t.scale = n.has("scale") ? n.at("scale").number(0, 3.4e38f, true) : 1.0f;
  t.a = n.at("a").color();
  t.b = n.at("b").color();
  return t;
}

// "uv_scale": [su, sv], "uv_offset": [ou, ov], "uv_rotate": DEGREES, each optional.
UvTransform parseUvTransform(const JsonNode& n) {
  const auto pair = [](const JsonNode& v) {
    if (!v.isArray() || v.size() != 2) v.fail("must be a pair [u, v]");
    return Vec2f{v[0].number(), v[1].number()};
  };
  const Vec2f scale = n.has("uv_scale") ? pair(n.at("uv_scale")) : Vec2f{1, 1};
  // Whole turns taken off first (fmod is exact): 3e38 degrees times π overflowed float, and
  // the texture went black.
  float degrees = n.has("uv_rotate") ? n.at("uv_rotate").number() : 0;
  if (std::fabs(degrees) > 360) degrees = std::fmod(degrees, 360.0f);
  const float angle = degrees * kPi / 180;
  return UvTransform::offsetRotateScale(n.has("uv_offset") ? pair(n.at("uv_offset")) : Vec2f{},
                                        angle, scale);
}

// The image file n.image names, relative to the scene file, in n.colorspace (or its default).
std::shared_ptr<const ImageTexture> parseImageFile(SceneBuilder& b, const JsonNode& n) {
  const JsonNode file = n.at("image");
  const std::filesystem::path rel(file.string());
  const std::string path =
      (rel.is_absolute() ? rel : std::filesystem::path(b.baseDir) / rel).lexically_normal();
  try {
    checkInputFile(path, kMaxTextureFileBytes, "texture");
  } catch (const GlintError& e) {
    file.fail(e.what());
  }
  try {
    return b.texture(path, n.has("colorspace") ? n.at("colorspace").string() : "");
  } catch (const OutOfMemoryError&) {
    throw;  // the machine's failure, not the file's
  } catch (const GlintError& e) {
    (n.has("colorspace") && dynamic_cast<const UsageError*>(&e) ? n.at("colorspace") : file)
        .fail(e.what());
  }
}

// {"image": FILE, "factor": [r, g, b], "colorspace": NAME, "uv_scale", "uv_offset",
//  "uv_rotate"}.
ColorTexture parseImageTexture(SceneBuilder& b, const JsonNode& n) {
  n.checkKeys({"image", "factor", "colorspace", "uv_scale", "uv_offset", "uv_rotate"});
  ColorTexture t;
  t.pattern = TexturePattern::Image;
  t.constant = n.has("factor") ? n.at("factor").color() : Rgb{1, 1, 1};
  t.uvTransform = parseUvTransform(n);
  t.image = parseImageFile(b, n);
  return t;
}

// "opacity": a coverage in [0, 1], or {"image": FILE, "factor": c, "uv_scale", "uv_offset",
// "uv_rotate"}: the image's alpha (its first channel if it has none) times c; with
// "opacity_cutoff" (default 0.5) it makes a cut-out (materials/cutout.h).
Cutout parseCutout(SceneBuilder& b, const JsonNode& material) {
  Cutout c;
  if (auto v = material.get("opacity_cutoff")) c.cutoff = v->number(0, 1);
  const JsonNode n = material.at("opacity");
  if (!n.isObject()) {
    c.coverage = n.number(0, 1);
    return c;
  }
  n.checkKeys({"image", "factor", "uv_scale", "uv_offset", "uv_rotate"});
  c.coverage = n.has("factor") ? n.at("factor").number(0, 1) : 1.0f;
  c.uvTransform = parseUvTransform(n);
  c.image = parseImageFile(b, n);
  c.channel = Cutout::Channel::AlphaElseGrey;
  return c;
}

// "normal_map" / "bump_map": {"image": FILE, "scale": s, "uv_scale", "uv_offset", "uv_rotate"}.
// The image is data (materials/normal_map.h): no "colorspace", its texels are read as stored.
template <class Map>
Map parseShadingMap(SceneBuilder& b, const JsonNode& n, float defaultScale) {
  if (!n.isObject()) n.fail("must be an object {\"image\": FILE, \"scale\": s}");
  n.checkKeys({"image", "scale", "uv_scale", "uv_offset", "uv_rotate"});
  Map map;
  map.scale = n.has("scale") ? n.at("scale").number(-1e6f, 1e6f) : defaultScale;
  map.uvTransform = parseUvTransform(n);
  map.image = parseImageFile(b, n);
  return map;
}

// A material's normal and bump maps; null when it has neither.
std::shared_ptr<const ShadingMaps> parseShadingMaps(SceneBuilder& b, const JsonNode& material) {
  if (!material.has("normal_map") && !material.has("bump_map")) return nullptr;
  auto maps = std::make_shared<ShadingMaps>();
  if (auto v = material.get("normal_map")) maps->normal = parseShadingMap<NormalMap>(b, *v, 1);
  if (auto v = material.get("bump_map")) maps->bump = parseShadingMap<BumpMap>(b, *v, 1);
  return maps;
}

ColorTexture parseColorTexture(SceneBuilder& b, const JsonNode& n) {
  if (n.isArray()) return ColorTexture::uniform(n.color());
  if (n.has("image")) return parseImageTexture(b, n);
  n.checkKeys({"checker", "noise", "marble", "wood", "image"});
  const std::vector<std::string> keys = n.keys();
  if (keys.size() != 1) n.fail("must name one texture: checker, noise, marble, wood or image");
  const std::string& kind = keys[0];
  const TexturePattern pattern = kind == "checker"  ? TexturePattern::Checker
                                 : kind == "noise"  ? TexturePattern::Noise
                                 : kind == "marble" ? TexturePattern::Marble
                                                    : TexturePattern::Wood;
  return parseSolidTexture(n.at(kind), pattern);
}

// "gloss" / "blur": a number, the width of seed 000's square (§13.4.4), or {"phong": n}, the
// exponent of seed 002's Phong lobe cosⁿ α (§9.3; n = 0 spreads over the whole hemisphere about
// the ideal direction).
float parseLobe(const JsonNode& n, GlossShape& shape) {
  if (n.isNumber()) {
    shape = GlossShape::Square;
    return n.number(0, 3.4e38f);
  }
  if (n.isObject()) {
    n.checkKeys({"phong"});
    if (n.has("phong")) {
      shape = GlossShape::Phong;
      return n.at("phong").number(0, 3.4e38f);
    }
  }
  n.fail(
      "must be a number (the width of seed 000's square) or {\"phong\": n} (seed 002's "
      "lobe cos^n about the ideal direction)");
}

// A dielectric's "fresnel": "exact", "schlick", or "none" with "kt" (seed 002 eq. 9.22: the
// interface transmits k_t, and km is its k_r).
void parseInterfaceCoefficients(const JsonNode& n, Dielectric& d) {
  const std::optional<JsonNode> fresnel = n.get("fresnel");
  const std::string model = fresnel ? fresnel->choice({"exact", "schlick", "none"}) : "exact";
  d.fresnel = model == "exact"     ? FresnelModel::Exact
              : model == "schlick" ? FresnelModel::Schlick
                                   : FresnelModel::None;
  const std::optional<JsonNode> kt = n.get("kt");
  if (!d.constantCoefficients()) {
    if (kt)
      kt->fail("applies with \"fresnel\": \"none\" only; under the " + model +
               " Fresnel law the interface transmits 1 − R");
    return;
  }
  if (!kt)
    fresnel->fail(
        "\"none\" needs \"kt\", the transmission coefficient k_t (seed 002 eq. 9.22) that "
        "replaces Fresnel's 1 − R");
  d.kt = kt->color();
  if (d.kt.maxChannel() > 1) kt->fail("each channel must be in [0, 1]");
}

// Every material type is the general surface of seed 002 §9.1 with its own defaults
// (materials/material.h); a dielectric adds its interface.
Material parseMaterial(SceneBuilder& b, const std::string& name, const JsonNode& n) {
  const std::string type = n.at("type").choice({"phong", "mirror", "dielectric"});
  const MaterialKind kind = type == "phong"    ? MaterialKind::Phong
                            : type == "mirror" ? MaterialKind::Mirror
                                               : MaterialKind::Dielectric;
  std::vector<std::string> keys = {"type",
                                   "ka",
                                   "kd",
                                   "ks",
                                   "km",
                                   "ke",
                                   "exponent",
                                   "specular_model",
                                   "gloss",
                                   "opacity",
                                   "opacity_cutoff",
                                   "normal_map",
                                   "bump_map"};
  static const std::vector<std::string> kInterfaceKeys = {"ior", "attenuation", "fresnel", "kt",
                                                          "blur"};
  if (kind == MaterialKind::Dielectric)
    keys.insert(keys.end(), kInterfaceKeys.begin(), kInterfaceKeys.end());
  else
    for (const std::string& key : kInterfaceKeys)  // clearer than a near name's "did you mean"
      if (auto v = n.get(key))
        v->fail("belongs to a \"dielectric\" material, not a \"" + type + "\" one");
  n.checkKeys(keys);
  Material m = defaultMaterial(kind);
  m.name = name;
  Surface& s = m.surface;
  if (auto v = n.get("kd")) {
    s.kd = parseColorTexture(b, *v);
    if (s.ambientFollowsDiffuse) s.ka = s.kd;  // k_a follows k_d unless given
  }
  if (auto v = n.get("ka")) s.ka = parseColorTexture(b, *v), s.ambientFollowsDiffuse = false;
  if (auto v = n.get("ks")) s.ks = parseColorTexture(b, *v);
  if (auto v = n.get("km")) s.km = parseColorTexture(b, *v);
  if (auto v = n.get("ke")) s.ke = parseColorTexture(b, *v);
  if (auto v = n.get("exponent")) s.exponent = v->number(0, 1e9f);
  if (auto v = n.get("specular_model"))
    s.specularModel =
        v->choice({"blinn", "phong"}) == "blinn" ? SpecularModel::BlinnPhong : SpecularModel::Phong;
  if (auto v = n.get("gloss")) s.gloss = parseLobe(*v, s.glossShape);
  s.normalMaps = parseShadingMaps(b, n);
  if (n.has("opacity"))
    m.cutout = parseCutout(b, n);
  else if (auto v = n.get("opacity_cutoff"))
    v->fail("needs an \"opacity\" to cut");
  if (kind != MaterialKind::Dielectric) return m;
  Dielectric& d = m.dielectric;
  if (auto v = n.get("ior")) d.ior = v->number(0, 1e3f, true);
  if (auto v = n.get("attenuation")) {
    const Rgb a = v->color();
    if (a.maxChannel() > 1) v->fail("each channel must be in [0, 1]");
    d.absorption = BeerMedium(a);
  }
  parseInterfaceCoefficients(n, d);
  if (auto v = n.get("blur")) d.blur = parseLobe(*v, d.blurShape);
  return m;
}

// {"type": "environment", "radiance": [r, g, b]}, or {"image": FILE, "colorspace": NAME,
// "intensity": s, "rotation": degrees}; either with "samples" (lights/environment.h).
EnvironmentLight parseEnvironment(SceneBuilder& b, const JsonNode& n) {
  n.checkKeys(
      {"type", "name", "radiance", "image", "colorspace", "intensity", "rotation", "samples"});
  const int samples = n.has("samples") ? n.at("samples").integer(1, 1 << 16) : 16;
  if (n.has("radiance") == n.has("image"))
    n.fail(std::string(n.has("image") ? "has both" : "needs one of") +
           " \"radiance\" (a uniform sky) and \"image\" (a lat-long image)");
  if (n.has("radiance")) {
    for (const char* key : {"colorspace", "intensity", "rotation"})
      if (n.has(key)) n.at(key).fail("applies to an environment \"image\" only");
    return EnvironmentLight(n.at("radiance").color(), samples);
  }
  const float intensity = n.has("intensity") ? n.at("intensity").number(0, 3.4e38f) : 1.0f;
  const float rotation = n.has("rotation") ? n.at("rotation").number(-1e6f, 1e6f) : 0.0f;
  const std::shared_ptr<const ImageTexture> texture = parseImageFile(b, n);
  const JsonNode file = n.at("image");
  LatLongImage image;
  try {
    image = readTexels(*texture, EnvironmentLight::bytesFor(1));
  } catch (const OutOfMemoryError&) {
    throw;  // the machine's failure, not the file's
  } catch (const GlintError& e) {
    file.fail(e.what());
  }
  // Radiance is finite and not negative (an EXR may hold anything): a NaN or a negative texel
  // would poison the sampling distribution and every pixel that sees it.
  for (size_t i = 0; i < image.texels.size(); ++i) {
    const Rgb& t = image.texels[i];
    if (t.isFinite() && t.r >= 0 && t.g >= 0 && t.b >= 0) continue;
    const size_t w = static_cast<size_t>(image.width);
    file.fail("texel (" + std::to_string(i % w) + ", " + std::to_string(i / w) + ") is (" +
              formatNumber(t.r) + ", " + formatNumber(t.g) + ", " + formatNumber(t.b) +
              "): an environment's radiance must be finite and >= 0");
  }
  return EnvironmentLight(std::move(image), intensity, rotation, samples);
}

Light parseLight(SceneBuilder& b, const JsonNode& n) {
  const std::string type =
      n.at("type").choice({"point", "spot", "directional", "quad", "disk", "environment"});
  if (type == "environment") return parseEnvironment(b, n);
  if (type == "point" || type == "spot") {
    std::vector<std::string> keys = {"type", "name", "position", "intensity", "falloff"};
    if (type == "spot") keys.insert(keys.end(), {"direction", "inner_angle", "outer_angle"});
    n.checkKeys(keys);
    PointLight l;
    l.position = b.toRender(n.at("position"));
    l.intensity = n.color("intensity", l.intensity);
    if (auto v = n.get("falloff"))
      l.falloff =
          v->choice({"none", "inverse_square"}) == "none" ? Falloff::None : Falloff::InverseSquare;
    if (type == "point") return l;
    // The cone's half-angles in degrees, glTF's defaults: full on the axis only, none past 45°.
    l.spotAxis = n.at("direction").direction();
    const float outer = n.has("outer_angle") ? n.at("outer_angle").number(0, 90, true) : 45;
    const float inner = n.has("inner_angle") ? n.at("inner_angle").number(0, 90) : 0;
    if (inner > outer) n.at("inner_angle").fail("must not be wider than outer_angle");
    l.cosInner = std::cos(inner * kPi / 180);
    l.cosOuter = std::cos(outer * kPi / 180);
    return l;
  }
  if (type == "directional") {
    n.checkKeys({"type", "name", "direction", "intensity"});
    DirectionalLight l;
    l.direction = n.at("direction").direction();
    l.intensity = n.color("intensity", l.intensity);
    return l;
  }
  const auto common = [&](auto& l) {
    l.intensity = n.color("intensity", l.intensity);
    if (auto v = n.get("samples")) l.samples = v->integer(1, 1 << 16);
    if (auto v = n.get("falloff"))
      l.falloff =
          v->choice({"none", "inverse_square"}) == "none" ? Falloff::None : Falloff::InverseSquare;
    if (auto v = n.get("emission"))
      l.emission = v->choice({"seed", "radiance"}) == "seed" ? Emission::Seed : Emission::Radiance;
    if (l.emission == Emission::Radiance && n.has("falloff"))
      n.at("falloff").fail("radiance emission always falls off with 1/r²; remove \"falloff\"");
    if (auto v = n.get("visible")) l.visible = v->boolean();
  };
  if (type == "quad") {
    n.checkKeys({"type", "name", "corner", "edge1", "edge2", "intensity", "samples", "falloff",
                 "emission", "visible"});
    const Vec3f corner = b.toRender(n.at("corner"));
    const Vec3f edge1 = n.at("edge1").vec3(), edge2 = n.at("edge2").vec3();
    if (!(length(cross(edge1, edge2)) > 0))
      n.fail("edge1 and edge2 must span a parallelogram (they are parallel or zero)");
    QuadLight l(corner, edge1, edge2);
    common(l);
    return l;
  }
  n.checkKeys({"type", "name", "center", "normal", "radius", "intensity", "samples", "falloff",
               "emission", "visible"});
  // Named before the constructor call: its arguments have no order of evaluation, and which
  // bad field is reported first should not depend on the compiler.
  const Vec3f center = b.toRender(n.at("center"));
  const Vec3f normal = n.at("normal").direction();
  DiskLight l(center, normal, n.at("radius").number(0, 3.4e38f, true));
  common(l);
  return l;
}

// A visible area light is also a surface of the world: a quad or disk where the light is, whose
// material emits the light's radiance (AreaEmission::emittedRadiance) and reflects nothing. Its
// object is named by the light (Scene::lightName).
void addLightSurfaces(SceneBuilder& b) {
  Scene& s = b.scene;
  for (size_t li = 0; li < s.lights.size(); ++li) {
    const auto* quad = std::get_if<QuadLight>(&s.lights[li]);
    const auto* disk = std::get_if<DiskLight>(&s.lights[li]);
    const AreaEmission* e = quad ? static_cast<const AreaEmission*>(quad) : disk;
    if (!e || !e->visible) continue;
    Material m = defaultMaterial(MaterialKind::Phong);
    m.name = "lights[" + std::to_string(li) + "]";
    m.surface.kd = m.surface.ka = ColorTexture{};
    m.surface.ke = ColorTexture::uniform(e->emittedRadiance(quad ? quad->area() : disk->area()));
    m.surface.emissionSides =
        e->emission == Emission::Radiance ? EmissionSides::Front : EmissionSides::Both;
    const auto materialId = static_cast<uint32_t>(s.materials.size());
    s.materials.push_back(std::move(m));
    Geometry g{GeomKind::Quad, 0, materialId, b.objectIdOf(s.lightName(li))};
    if (quad) {
      g.index = static_cast<uint32_t>(s.quads.size());
      s.quads.push_back({quad->corner(), quad->edge1(), quad->edge2()});
    } else {
      g.kind = GeomKind::Disk;
      g.index = static_cast<uint32_t>(s.disks.size());
      s.disks.push_back({disk->center(), disk->normal(), disk->radius()});
    }
    s.groups[0].geometries.push_back(g);
  }
}

// The lights, at most one of them an environment, which replaces render.background.
void parseLights(SceneBuilder& b, const JsonNode& root, const JsonNode& lights) {
  Scene& s = b.scene;
  std::string environmentAt;
  for (const JsonNode& l : lights.elements()) {
    const std::optional<JsonNode> type = l.isObject() ? l.get("type") : std::nullopt;
    const bool environment = type && type->isString() && type->string() == "environment";
    // Refused before the second image is read.
    if (environment && !environmentAt.empty())
      l.fail("a second environment light: a scene has at most one (" + environmentAt + ")");
    s.lights.push_back(parseLight(b, l));
    s.lightNames.push_back(l.has("name") ? b.claimName(l.at("name")) : "");
    if (!environment) continue;
    environmentAt = l.path();
    s.environment = std::get<EnvironmentLight>(s.lights.back());
    // Both would say what rays that leave the scene see.
    if (auto render = root.get("render"); render && render->has("background"))
      render->at("background")
          .fail("rays that miss see the environment (" + environmentAt +
                "); remove \"background\", or the environment");
  }
}

// Drops the ids of names nothing in the world shows (an object whose mesh file names every
// triangle), so that the ids the objectid AOV writes run 1, 2, 3 ... without gaps.
void dropUnshownObjectIds(Scene& s) {
  const std::vector<bool> shown = s.objectIdsInWorld();
  std::vector<uint32_t> newId(shown.size(), 0);
  std::vector<std::string> names;
  for (size_t i = 0; i < shown.size(); ++i)
    if (shown[i]) {
      newId[i] = static_cast<uint32_t>(names.size());
      names.push_back(s.objectNames[i]);
    }
  if (names.size() == s.objectNames.size()) return;
  // An entry whose id nothing shows is a mesh whose triangles carry theirs (or an instance of
  // one): its own is never read.
  for (Geometry& g : s.groups[0].geometries) g.objectId = newId[g.objectId];
  for (TriangleMesh& m : s.meshes)
    for (uint32_t& id : m.objectIds) id = newId[id];
  s.objectNames = std::move(names);
}

void parseScene(SceneBuilder& b, const JsonNode& root, std::optional<int> frame) {
  root.checkKeys({"animation", "render", "camera", "materials", "lights", "objects", "groups"});
  Scene& s = b.scene;
  s.animation = parseAnimation(root.get("animation"), frame);
  if (auto n = root.get("render")) parseRender(*n, s.render);
  parseCamera(root.at("camera"), s.animation, s.cameraDesc, s.worldOrigin);

  if (auto mats = root.get("materials"))
    for (const std::string& name : mats->keys()) {
      b.materialIds[name] = static_cast<uint32_t>(s.materials.size());
      s.materials.push_back(parseMaterial(b, name, mats->at(name)));
    }
  if (auto lights = root.get("lights")) parseLights(b, root, *lights);

  s.groups.push_back({"", {}});
  // Groups are registered before objects so instances can name them in any order.
  std::optional<JsonNode> groups = root.get("groups");
  if (groups)
    for (const std::string& name : groups->keys()) {
      b.groupIds[name] = static_cast<uint32_t>(s.groups.size());
      s.groups.push_back({name, {}});
    }
  if (groups)
    for (const std::string& name : groups->keys()) {
      const JsonNode members = groups->at(name);
      for (size_t i = 0; i < members.size(); ++i) {
        if (members[i].isObject() && members[i].has("name"))
          members[i].at("name").fail(
              "a group's members have no names of their own: each instance of the group is one "
              "object, named by the instance's \"name\"");
        addObject(b, members[i], b.groupIds[name], static_cast<uint32_t>(i));
      }
    }
  // Ids follow the order names are first met; an unnamed object is "objects[i]", the path
  // Glint's errors use, which stays the same from frame to frame.
  const JsonNode objects = root.at("objects");
  for (size_t i = 0; i < objects.size(); ++i) {
    const JsonNode obj = objects[i];
    const std::string given =
        obj.isObject() && obj.has("name") ? b.claimName(obj.at("name")) : std::string();
    const uint32_t id = b.objectIdOf(given.empty() ? "objects[" + std::to_string(i) + "]" : given);
    b.partPrefix = given;
    addObject(b, obj, 0, id);
    b.partPrefix.reset();
  }
  addLightSurfaces(b);
  dropUnshownObjectIds(s);
  // An animated scene's keys span its frames: keep just this frame's shutter of them.
  if (s.animation) resampleMotionToFrame(s, *s.animation);
  s.features = computeFeatures(s);
  if (!s.animation && s.features.motion && s.cameraDesc.shutterOpen == s.cameraDesc.shutterClose)
    log::warning(b.scene.sourcePath + ": the scene has motion keys but camera.shutter is closed (" +
                 "[" + std::to_string(s.cameraDesc.shutterOpen) + ", " +
                 std::to_string(s.cameraDesc.shutterClose) +
                 "]): it renders frozen at that time; set \"shutter\": [0, 1] for motion blur");
}

}  // namespace

Scene loadSceneText(const std::string& text, const std::string& fileName,
                    const std::string& baseDir, std::optional<int> frame) {
  checkJsonTreeFits(text, kSceneBytesPerValue, kSceneBytesPerLine, "scene " + fileName);
  const JsonDocument doc(text, fileName);
  SceneBuilder b;
  b.baseDir = baseDir;
  b.scene.sourcePath = fileName;
  b.scene.sourceHash = hashBytes(text);
  parseScene(b, JsonNode(doc, doc.root(), "", ""), frame);
  return std::move(b.scene);
}

Scene loadSceneFile(const std::string& path, std::optional<int> frame) {
  const std::string text = readInputFile(path, kMaxSceneFileBytes, "JSON scene");
  const std::filesystem::path p(path);
  return loadSceneText(text, path, p.parent_path().string(), frame);
}

}  // namespace glint
