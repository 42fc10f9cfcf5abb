#pragma once
// Turns per-sample AOV records into film planes (docs/output.md): depth is the nearest hit over
// the pixel's samples (kBackgroundDepth where none hit); normal, position, albedo, direct,
// indirect and per-light values are averaged over all samples (misses add zero, so they are
// premultiplied by coverage like the beauty); the object id is the most frequent one (ties go to
// the smaller id), a float like Blender's IndexOB pass; variance is the estimated variance of the
// pixel's mean beauty (render/pixel_estimate.h). Cryptomatte ranks the objects and materials of
// the pixel's first hits by their share of its samples.
//
// A render adds a pixel's samples pass by pass: while it runs, the film's AOV planes hold sums
// (depth: the nearest hit so far, 0 for none) and AovTables the id counts; resolveAovs turns
// them into the planes written out.
#include <cstdint>
#include <string>
#include <vector>

#include "film/film.h"
#include "integrator/aov.h"
#include "integrator/radiance.h"
#include "render/coverage_table.h"
#include "render/pixel_estimate.h"
#include "scene/scene.h"

namespace glint {

// The depth written where no sample hit anything; a hit farther away is written as it too, so
// that a Z-combine never puts the background in front of the scene. Blender writes 1e10 there;
// +Inf cannot be written (an EXR from Glint holds no Inf: exr_output.h) and would turn every
// difference a tool takes with it into Inf or NaN. 1e10 is exact in float.
inline constexpr double kBackgroundDepth = 1e10;

// The largest object id written (objects[] index + 1): every integer up to 2^24 is exact in the
// float channel that Blender's IndexOB pass is.
inline constexpr uint32_t kMaxObjectIdAov = uint32_t{1} << 24;

// The longest light layer name made from a light's name: OpenEXR cuts channel names at 255
// bytes, and a layer name is typed in compositors.
inline constexpr size_t kMaxLightLayerName = 64;

// The layer of each light's AOV (docs/output.md): "light_NAME" for a light with a name, the
// name cut to kMaxLightLayerName bytes with each character but ASCII letters, digits, '_' and
// '-' made one '_' (so that every EXR reader splits LAYER.R where Glint does); "lightK" for an
// unnamed light K. A layer another light already has takes "_K" until it is unique.
std::vector<std::string> lightLayerNames(const Scene& scene);

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
  // AOVs with too many lights, and for object ids beyond kMaxObjectIdAov.
  static AovLayout create(const AovSet& set, const Scene& scene, Film& film);
};

// Each pixel's counts of the object ids and materials its samples saw, kept between passes
// only for the AOVs that rank them (object id, Cryptomatte).
struct AovTables {
  AovTables(const AovLayout& layout, const PixelWindow& window);
  CoverageTable* objectIds(int x, int y) { return at(objectIds_, x, y); }
  CoverageTable* cryptoObjects(int x, int y) { return at(cryptoObjects_, x, y); }
  CoverageTable* cryptoMaterials(int x, int y) { return at(cryptoMaterials_, x, y); }
  const CoverageTable* objectIds(int x, int y) const { return at(objectIds_, x, y); }
  const CoverageTable* cryptoObjects(int x, int y) const { return at(cryptoObjects_, x, y); }
  const CoverageTable* cryptoMaterials(int x, int y) const { return at(cryptoMaterials_, x, y); }

 private:
  template <class Tables>
  auto at(Tables& tables, int x, int y) const -> decltype(tables.data()) {
    if (tables.empty()) return nullptr;
    return tables.data() + size_t(y - window_.y0) * size_t(window_.width()) +
           size_t(x - window_.x0);
  }
  PixelWindow window_;
  std::vector<CoverageTable> objectIds_, cryptoObjects_, cryptoMaterials_;
};

// One pixel's samples of one pass: begin, add each sample, then commit adds them to the film's
// sums and the pixel's tables.
class PixelAovs {
 public:
  explicit PixelAovs(const AovLayout& layout) : layout_(layout) {}
  void begin();
  void add(const Radiance& r, const AovSample& s);
  void commit(Film& sums, AovTables& tables, int x, int y) const;

 private:
  const AovLayout& layout_;
  double minDepth_ = 0;
  bool anyHit_ = false;
  double normal_[3], position_[3], albedo_[3], direct_[3], indirect_[3];
  double lights_[3 * AovSet::kMaxLights];
  CoverageTable ids_;                              // object ids
  CoverageTable cryptoObjects_, cryptoMaterials_;  // object ids (from 0) and material indices
};

// The finished AOV planes of `out` (a film with the same planes as `sums`) for pixel (x, y).
void resolveAovs(const AovLayout& layout, const Film& sums, const AovTables& tables,
                 const PixelEstimate& pixel, Film& out, int x, int y);

}  // namespace glint
