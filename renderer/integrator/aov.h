#pragma once
// Arbitrary output variables: what the first camera hit was, besides the beauty. The integrator
// fills an AovSample only when AOVs were asked for (a null pointer otherwise), so a beauty-only
// render does none of this work. Names and channel conventions are in docs/output.md.
#include <cstdint>
#include <string>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

enum class Aov : uint32_t {
  Depth = 1,       // Z: distance along the camera's view axis (1e10 where nothing was hit)
  Normal = 2,      // N: world-space shading normal, facing the camera
  Albedo = 4,      // k_d (Phong), k_m (mirror), 1 (dielectric)
  Position = 8,    // P: world-space hit point
  ObjectId = 16,   // IndexOB.X: objects[] index + 1, 0 = background (float)
  Direct = 32,     // local shading at the first hit (ambient + lights)
  Indirect = 64,   // everything else: reflection, refraction and the background seen
  Lights = 128,    // direct light per light source (light_NAME, or lightK if unnamed)
  Variance = 256,  // variance of the beauty pixel estimate
  // Cryptomatte object and material layers: ranked (ID, coverage) pairs of the first hits
  Cryptomatte = 512,
};

class AovSet {
 public:
  static constexpr int kMaxLights = 16;  // per-light AOVs keep the per-ray path allocation-free

  // "depth,normal,albedo,..." → set; throws UsageError naming an unknown AOV.
  static AovSet parse(const std::string& list);
  static const std::vector<std::string>& names();

  bool has(Aov a) const { return (bits_ & static_cast<uint32_t>(a)) != 0; }
  bool any() const { return bits_ != 0; }
  // Whether the integrator must fill per-sample data (variance needs only the beauty).
  bool needsSamples() const { return (bits_ & ~static_cast<uint32_t>(Aov::Variance)) != 0; }
  void add(Aov a) { bits_ |= static_cast<uint32_t>(a); }

 private:
  uint32_t bits_ = 0;
};

// The plane an AOV of fixed channels is written as: the AOV's name and its EXR channels, named
// as Blender, tev and pbrt-v4 name them where they have a name (docs/output.md). Per-light and
// Cryptomatte planes are named after the scene instead.
struct AovPlane {
  Aov aov;
  std::string name;
  std::vector<std::string> channels;
};
const AovPlane& aovPlane(Aov aov);  // for every AOV but Lights and Cryptomatte
// The channels of an RGB plane named `layer`: layer.R, layer.G, layer.B.
std::vector<std::string> rgbChannels(const std::string& layer);
// The AOV whose plane has exactly these channels, or null: how a frame read back names its
// layers as the render did.
const AovPlane* aovPlaneWithChannels(const std::vector<std::string>& channels);

struct AovSample {
  Vec3f viewAxis;  // in: the camera's unit view direction (depth is measured along it)
  bool hit = false;
  float depth = 0;
  Vec3f normal, position;
  Rgb albedo;
  uint32_t objectId = 0;
  uint32_t materialId = 0;  // the hit's materials[] index (no + 1: read only for a hit)
  Rgb direct;
  Rgb perLight[AovSet::kMaxLights];
};

}  // namespace glint
