#pragma once
// The environment light: radiance arriving from infinitely far away in every direction, either
// one colour (a uniform sky) or a lat-long (equirectangular) image. It is what rays that leave
// the scene see, and it lights surfaces through shadow rays sampled in proportion to what it
// sends (docs/effects.md, "Environment light"):
//  - a uniform sky by a cosine-weighted hemisphere about the shading normal, so that a diffuse
//    surface in the open reads k_d·π·L exactly;
//  - an image by a piecewise-constant distribution over its texels, luminance × sin θ.
// Orientation (SCENE_FORMAT.md): the top row looks along +Y, the image's centre along −Z, +X
// lies to its right; `rotation` turns the environment about +Y, counter-clockwise seen from
// above, so that with 90° the centre looks along −X.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

// A lat-long image as the environment reads it: scene-linear texels, row 0 at the top.
struct LatLongImage {
  int width = 0, height = 0;
  std::vector<Rgb> texels;  // width × height, row by row
};

// A sampled direction of the environment: unit wi (world) and the radiance along it divided by
// the probability density of choosing it (per steradian): one sample's estimate of ∫ L dω
// weighted by what the surface does with it.
struct EnvironmentSample {
  Vec3f wi;
  Rgb radianceOverPdf;
};

class EnvironmentLight {
 public:
  // A uniform sky of radiance L.
  EnvironmentLight(const Rgb& radiance, int samples);
  // An image, its texels scaled by `intensity`, turned by `rotationDegrees` about +Y. Builds the
  // sampling distribution: about 12 bytes per texel beside the image's 12.
  EnvironmentLight(LatLongImage image, float intensity, float rotationDegrees, int samples);

  int samples = 16;  // shadow rays per shading point

  bool isUniform() const { return !map_; }
  // The radiance arriving along -d, that is, what a ray leaving along d (any length) sees.
  Rgb radiance(const Vec3f& d) const;
  // A direction drawn for a point whose unit shading normal is n, u in [0, 1)². A direction
  // with zero density (below the horizon of a uniform sky, or a black image) comes back with
  // black radianceOverPdf.
  EnvironmentSample sample(const Vec3f& n, Vec2f u) const;
  // sample() for `count` draws u[i] at once, into out[i]: the same directions and values.
  void sample(const Vec3f& n, const Vec2f* u, int count, EnvironmentSample* out) const;
  // The density, per steradian, with which sample() draws unit direction d for a point whose
  // unit shading normal is n (an image's does not depend on n; a uniform sky's is cos θ/π).
  float pdf(const Vec3f& n, const Vec3f& d) const;

  // Bytes an image of `texels` texels takes with its distribution (the loader checks that they
  // fit the memory budget before any is made).
  static double bytesFor(double texels) { return 24 * texels; }

 private:
  struct Map;
  EnvironmentSample sampleUniform(const Vec3f& n, Vec2f u) const;
  Rgb uniform_;
  std::shared_ptr<const Map> map_;  // null for a uniform sky
};

}  // namespace glint
