#include "render/aov_accumulator.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.h"
#include "film/cryptomatte.h"

namespace glint {

namespace {

// The names of the scene's object ids, and whether each is shown by something in the world
// (an id registered for an object whose triangles all name others shows nothing).
std::vector<std::string> objectNamesOf(const Scene& scene, std::vector<bool>& inWorld) {
  inWorld = scene.objectIdsInWorld();
  std::vector<std::string> names(inWorld.size());
  for (uint32_t i = 0; i < names.size(); ++i) names[i] = scene.objectName(i);
  return names;
}

// The objectid AOV's manifest: {"ID": name} of every id in the world (ID = object id + 1, as
// IndexOB.X holds it), in the ids' order.
std::string objectIdManifest(const std::vector<std::string>& names,
                             const std::vector<bool>& inWorld) {
  nlohmann::ordered_json manifest = nlohmann::ordered_json::object();
  for (size_t i = 0; i < names.size(); ++i)
    if (inWorld[i]) manifest[std::to_string(i + 1)] = names[i];
  return manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// Adds one Cryptomatte type: its layers, and its manifest of the names in `listed`.
size_t addCryptomatte(Film& film, const std::string& typeName,
                      const std::vector<std::string>& names, const std::vector<bool>& listed,
                      std::vector<float>& ids) {
  std::vector<std::string> manifest;
  ids.resize(names.size());
  for (size_t i = 0; i < names.size(); ++i) {
    ids[i] = cryptomatteId(names[i]);
    if (listed[i]) manifest.push_back(names[i]);
  }
  return addCryptomatteLayers(film, typeName, manifest);
}

}  // namespace

std::vector<std::string> lightLayerNames(const Scene& scene) {
  std::vector<std::string> layers;
  std::set<std::string> taken;
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    const bool named = k < scene.lightNames.size() && !scene.lightNames[k].empty();
    std::string layer = named ? "light_" : "light" + std::to_string(k);
    if (named) {
      for (const char ch : scene.lightNames[k]) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '_' || c == '-')
          layer += ch;
        else if ((c & 0xc0) != 0x80)  // a UTF-8 character's continuation bytes add nothing
          layer += '_';
        if (layer.size() >= kMaxLightLayerName) break;
      }
      while (taken.count(layer)) layer += "_" + std::to_string(k);
    }
    taken.insert(layer);
    layers.push_back(layer);
  }
  return layers;
}

AovLayout AovLayout::create(const AovSet& set, const Scene& scene, Film& film) {
  const size_t lightCount = scene.lights.size();
  AovLayout l;
  l.set = set;
  l.lights = lightCount;
  const auto add = [&](Aov aov) {
    const AovPlane& p = aovPlane(aov);
    return film.addPlane(p.name, p.channels);
  };
  if (set.has(Aov::Depth)) l.depth = add(Aov::Depth);
  if (set.has(Aov::Normal)) l.normal = add(Aov::Normal);
  if (set.has(Aov::Albedo)) l.albedo = add(Aov::Albedo);
  if (set.has(Aov::Position)) l.position = add(Aov::Position);
  if (set.has(Aov::ObjectId)) {
    std::vector<bool> inWorld;
    const std::vector<std::string> names = objectNamesOf(scene, inWorld);
    const uint64_t ids = names.size();
    if (ids > kMaxObjectIdAov)
      throw UsageError("--aov objectid: the scene has " + std::to_string(ids) +
                       " object ids; the float channel holds ids up to " +
                       std::to_string(kMaxObjectIdAov) + " exactly (use --aov cryptomatte)");
    l.objectId = add(Aov::ObjectId);
    film.addAttribute("glint:objectid_manifest", objectIdManifest(names, inWorld));
  }
  if (set.has(Aov::Direct)) l.direct = add(Aov::Direct);
  if (set.has(Aov::Indirect)) l.indirect = add(Aov::Indirect);
  if (set.has(Aov::Lights)) {
    if (lightCount > size_t(AovSet::kMaxLights))
      throw UsageError("--aov lights: the scene has " + std::to_string(lightCount) +
                       " lights; per-light AOVs support at most " +
                       std::to_string(AovSet::kMaxLights));
    const std::vector<std::string> layers = lightLayerNames(scene);
    nlohmann::ordered_json names = nlohmann::ordered_json::object();
    for (size_t i = 0; i < lightCount; ++i) {
      const size_t p = film.addPlane(layers[i], rgbChannels(layers[i]));
      if (i == 0) l.firstLight = p;
      names[layers[i]] = scene.lightName(i);
    }
    // Which light each layer is, by its full name (the layer's is sanitised).
    film.addAttribute("glint:light_layers",
                      names.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
  if (set.has(Aov::Variance)) l.variance = add(Aov::Variance);
  if (set.has(Aov::Cryptomatte)) {
    std::vector<bool> inWorld;
    const std::vector<std::string> objects = objectNamesOf(scene, inWorld);
    l.cryptoObject = addCryptomatte(film, "CryptoObject", objects, inWorld, l.objectCryptoIds);
    std::vector<std::string> materials;
    for (const Material& m : scene.materials) materials.push_back(m.name);
    l.cryptoMaterial =
        addCryptomatte(film, "CryptoMaterial", materials, std::vector<bool>(materials.size(), true),
                       l.materialCryptoIds);
  }
  return l;
}

AovTables::AovTables(const AovLayout& layout, const PixelWindow& window) : window_(window) {
  const auto pixels = static_cast<size_t>(window.area());
  if (layout.objectId != SIZE_MAX) objectIds_.resize(pixels);
  if (layout.cryptoObject != SIZE_MAX) {
    cryptoObjects_.resize(pixels);
    cryptoMaterials_.resize(pixels);
  }
}

void PixelAovs::begin() {
  anyHit_ = false;
  minDepth_ = 0;
  std::fill(std::begin(normal_), std::end(normal_), 0.0);
  std::fill(std::begin(position_), std::end(position_), 0.0);
  std::fill(std::begin(albedo_), std::end(albedo_), 0.0);
  std::fill(std::begin(direct_), std::end(direct_), 0.0);
  std::fill(std::begin(indirect_), std::end(indirect_), 0.0);
  std::fill(std::begin(lights_), std::end(lights_), 0.0);
  ids_.clear();
  cryptoObjects_.clear();
  cryptoMaterials_.clear();
}

void PixelAovs::add(const Radiance& r, const AovSample& s) {
  // A non-finite sample counts as black in every plane: its record (which may hold the
  // non-finite values) is not used, so nothing non-finite reaches the EXR.
  if (!r.valid) return;
  // A miss is the background the camera sees: none of the surface's planes, and all of the
  // beauty's share past the direct light, so that direct + indirect is the beauty everywhere.
  if (!s.hit) {
    indirect_[0] += r.L.r, indirect_[1] += r.L.g, indirect_[2] += r.L.b;
    return;
  }
  if (!anyHit_ || s.depth < minDepth_) minDepth_ = s.depth;
  anyHit_ = true;
  const auto addVec = [](double* acc, const Vec3f& v) {
    acc[0] += v.x, acc[1] += v.y, acc[2] += v.z;
  };
  const auto addRgb = [](double* acc, const Rgb& v) {
    acc[0] += v.r, acc[1] += v.g, acc[2] += v.b;
  };
  addVec(normal_, s.normal);
  addVec(position_, s.position);
  addRgb(albedo_, s.albedo);
  addRgb(direct_, s.direct);
  addRgb(indirect_, {r.L.r - s.direct.r, r.L.g - s.direct.g, r.L.b - s.direct.b});
  for (size_t i = 0; i < layout_.lights && i < size_t(AovSet::kMaxLights); ++i)
    addRgb(&lights_[3 * i], s.perLight[i]);
  if (layout_.objectId != SIZE_MAX) ids_.add(s.objectId);
  if (layout_.cryptoObject != SIZE_MAX) {
    cryptoObjects_.add(s.objectId - 1);
    cryptoMaterials_.add(s.materialId);
  }
}

void PixelAovs::commit(Film& sums, AovTables& tables, int x, int y) const {
  const auto addTo = [&](size_t plane, const double* acc) {
    if (plane == SIZE_MAX) return;
    double* sum = sums.planePixel(plane, x, y);
    for (int c = 0; c < 3; ++c) sum[c] += acc[c];
  };
  if (layout_.depth != SIZE_MAX && anyHit_) {
    // Hits are at t > 0, so 0 marks a pixel that no pass has seen hit yet.
    double& depth = *sums.planePixel(layout_.depth, x, y);
    if (depth == 0 || minDepth_ < depth) depth = minDepth_;
  }
  addTo(layout_.normal, normal_);
  addTo(layout_.position, position_);
  addTo(layout_.albedo, albedo_);
  addTo(layout_.direct, direct_);
  addTo(layout_.indirect, indirect_);
  if (layout_.firstLight != SIZE_MAX)
    for (size_t i = 0; i < layout_.lights; ++i) addTo(layout_.firstLight + i, &lights_[3 * i]);
  if (CoverageTable* t = tables.objectIds(x, y)) t->add(ids_);
  if (CoverageTable* t = tables.cryptoObjects(x, y)) t->add(cryptoObjects_);
  if (CoverageTable* t = tables.cryptoMaterials(x, y)) t->add(cryptoMaterials_);
}

namespace {

// Writes the table's first kCryptomatteRanks ranks into the layers from `firstPlane` on.
void putCryptomatte(Film& film, int x, int y, size_t firstPlane, const CoverageTable& table,
                    const std::vector<float>& ids, double samples) {
  // Coverage is the share of all the pixel's samples (the beauty's box filter), so the
  // background's share is what the ranks leave of 1. Ranks that nothing fills are ID 0,
  // coverage 0, as the specification asks.
  const CoverageTable ranked = table.ranked();
  const double inv = samples > 0 ? 1.0 / samples : 0;
  for (int layer = 0; layer < (kCryptomatteRanks + 1) / 2; ++layer) {
    double v[4] = {0, 0, 0, 0};
    for (int k = 0; k < 2; ++k) {
      const int rank = 2 * layer + k;
      if (rank >= ranked.size() || rank >= kCryptomatteRanks) continue;
      v[2 * k] = ids[ranked[rank].id];
      v[2 * k + 1] = ranked[rank].count * inv;
    }
    film.setPlanePixel(firstPlane + size_t(layer), x, y, v);
  }
}

}  // namespace

void resolveAovs(const AovLayout& layout, const Film& sums, const AovTables& tables,
                 const PixelEstimate& pixel, Film& out, int x, int y) {
  const double samples = static_cast<double>(pixel.samples());
  const double inv = samples > 0 ? 1.0 / samples : 0;
  const auto average = [&](size_t plane) {
    if (plane == SIZE_MAX) return;
    const double* sum = sums.planePixel(plane, x, y);
    const double v[3] = {sum[0] * inv, sum[1] * inv, sum[2] * inv};
    out.setPlanePixel(plane, x, y, v);
  };
  if (layout.depth != SIZE_MAX) {
    const double nearest = *sums.planePixel(layout.depth, x, y);
    const double depth = nearest == 0 ? kBackgroundDepth : std::min(nearest, kBackgroundDepth);
    out.setPlanePixel(layout.depth, x, y, &depth);
  }
  average(layout.normal);
  average(layout.position);
  average(layout.albedo);
  average(layout.direct);
  average(layout.indirect);
  if (layout.firstLight != SIZE_MAX)
    for (size_t i = 0; i < layout.lights; ++i) average(layout.firstLight + i);
  if (const CoverageTable* ids = tables.objectIds(x, y)) {
    // ranked() puts the most frequent first, ties to the smaller id.
    const double id = ids->size() > 0 ? ids->ranked()[0].id : 0;
    out.setPlanePixel(layout.objectId, x, y, &id);
  }
  if (layout.cryptoObject != SIZE_MAX) {
    putCryptomatte(out, x, y, layout.cryptoObject, *tables.cryptoObjects(x, y),
                   layout.objectCryptoIds, samples);
    putCryptomatte(out, x, y, layout.cryptoMaterial, *tables.cryptoMaterials(x, y),
                   layout.materialCryptoIds, samples);
  }
  if (layout.variance != SIZE_MAX) {
    // The halves' estimate (pixel_estimate.h), 0 where a pixel has one sample and none can be
    // made. Finite for any float samples (a squared difference of two is below 1e78); the EXR
    // writer clamps what is beyond the channel's type, and counts it.
    double v[3] = {0, 0, 0};
    pixel.varianceOfMean(v);
    out.setPlanePixel(layout.variance, x, y, v);
  }
}

}  // namespace glint
