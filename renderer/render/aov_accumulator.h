#pragma once
// Turns per-sample AOV records into film planes, one pixel at a time (docs/output.md):
// depth is the nearest hit over the pixel's samples; normal, position, albedo, direct,
// indirect and per-light values are averaged over all samples (misses add zero, so they are
// premultiplied by coverage like the beauty); the object id is the most frequent one (ties go
// to the smaller id); variance is that of the pixel's mean beauty, s²/n. Cryptomatte ranks the
// objects and materials of the pixel's first hits by their share of its samples.
#include <cstdint>
#include <vector>

#include "film/film.h"
#include "integrator/aov.h"
#include "integrator/radiance.h"
#include "render/coverage_table.h"
#include "scene/scene.h"

namespace glint {

struct AovLayout {
  AovSet set;
  size_t lights = 0;
  // Plane index per AOV in the film, or SIZE_MAX when not requested.
  size_t depth = SIZE_MAX, normal = SIZE_MAX, albedo = SIZE_MAX, position = SIZE_MAX,
         objectId = SIZE_MAX, direct = SIZE_MAX, indirect = SIZE_MAX, variance = SIZE_MAX;
  size_t firstLight = SIZE_MAX;
  // The first of the CryptoObject and CryptoMaterial layers, and each object id's and
  // material's Cryptomatte ID.
  size_t cryptoObject = SIZE_MAX, cryptoMaterial = SIZE_MAX;
  std::vector<float> objectCryptoIds, materialCryptoIds;

  // Adds the planes (and the metadata they need) to the film. Throws UsageError for per-light
  // AOVs with too many lights.
  static AovLayout create(const AovSet& set, const Scene& scene, Film& film);
};

class PixelAovs {
 public:
  explicit PixelAovs(const AovLayout& layout) : layout_(layout) {}
  void begin();
  void add(const Radiance& r, const AovSample& s);
  void end(Film& film, int x, int y) const;

 private:
  // Writes the table's first kCryptomatteRanks ranks into the layers from `firstPlane` on.
  void putCryptomatte(Film& film, int x, int y, size_t firstPlane, const CoverageTable& table,
                      const std::vector<float>& ids) const;

  const AovLayout& layout_;
  int n_ = 0;
  double minDepth_ = 0;
  bool anyHit_ = false;
  double normal_[3], position_[3], albedo_[3], direct_[3], indirect_[3];
  double lights_[3 * AovSet::kMaxLights];
  double mean_[3], m2_[3];  // Welford over the beauty
  std::vector<std::pair<uint32_t, int>> ids_;
  CoverageTable cryptoObjects_, cryptoMaterials_;  // object ids (from 0) and material indices
};

}  // namespace glint
