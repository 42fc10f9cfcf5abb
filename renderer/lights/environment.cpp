#include "lights/environment.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "core/frame.h"
#include "core/lanes.h"
#include "core/sampling.h"
#include "core/sin_cos.h"
#include "lights/guided_cdf.h"

namespace glint {

namespace {

// Rec. 709 luminance: what the eye, and a grey surface, take of a colour.
double luminance(const Rgb& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Builds a cumulative table of `n` non-negative weights, normalised to end at exactly 1;
// returns their total (0: all zero, and the table stays 0).
double cumulate(const double* weight, int n, float* cdf) {
  double total = 0;
  cdf[0] = 0;
  for (int i = 0; i < n; ++i) total += weight[i];
  double running = 0;
  for (int i = 0; i < n; ++i) {
    running += weight[i];
    cdf[i + 1] = total > 0 ? static_cast<float>(running / total) : 0.0f;
  }
  if (total > 0) cdf[n] = 1;
  return total;
}

}  // namespace

// The image and a 2-D piecewise-constant distribution over its (u, v) square: a row (θ) from
// the marginal table, then a texel (φ) from that row's conditional table.
struct EnvironmentLight::Map {
  LatLongImage image;           // scaled by intensity
  float rotation = 0;           // radians about +Y
  std::vector<float> rowCdf;    // height + 1
  std::vector<float> texelCdf;  // per row, width + 1
  // Their guides (lights/guided_cdf.h): without them the two binary searches were the largest
  // part of a sample.
  int rowBins = 1, texelBins = 1;
  std::vector<uint32_t> rowGuide;    // rowBins + 1
  std::vector<uint32_t> texelGuide;  // per row, texelBins + 1

  GuidedCdf rows() const { return {rowCdf.data(), image.height, rowGuide.data(), rowBins}; }
  GuidedCdf texelsOfRow(int y) const {
    const auto row = static_cast<size_t>(y);
    return {texelCdf.data() + row * (static_cast<size_t>(image.width) + 1), image.width,
            texelGuide.data() + row * (static_cast<size_t>(texelBins) + 1), texelBins};
  }
  // Per texel, the density over the (u, v) square with which it is drawn: its weight over the
  // mean weight (0 everywhere when the image is black).
  std::vector<float> density;

  // Where texel (x, y) is in image.texels and density.
  size_t indexOf(int x, int y) const {
    return static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x);
  }
  const Rgb& texel(int x, int y) const { return image.texels[indexOf(x, y)]; }
  // A sample's place in the (u, v) square: its row y (θ) from the marginal table, its texel x
  // (φ) from that row's conditional table, and where in the texel it lies.
  struct Cell {
    int x, y;
    float withinTexel, withinRow;
  };
  Cell cellOf(Vec2f u) const {
    Cell c;
    c.y = rows().find(u.y, c.withinRow);
    c.x = texelsOfRow(c.y).find(u.x, c.withinTexel);
    // What sampleAt reads next, fetched while the next samples' tables are searched.
    const size_t i = indexOf(c.x, c.y);
    __builtin_prefetch(&density[i]);
    __builtin_prefetch(&image.texels[i]);
    return c;
  }
  // The direction at a cell and the radiance along it over the density of drawing it.
  EnvironmentSample sampleAt(const Cell& c) const {
    EnvironmentSample s;
    const int w = image.width, h = image.height;
    const float theta = kPi * (static_cast<float>(c.y) + c.withinRow) / static_cast<float>(h);
    const float phi =
        2 * kPi * ((static_cast<float>(c.x) + c.withinTexel) / static_cast<float>(w) - 0.5f) -
        rotation;
    const float sinTheta = std::sin(theta);
    s.wi = {sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi)};
    const float d = density[indexOf(c.x, c.y)];
    // The (u, v) square maps onto the sphere with dω = 2π² sin θ du dv.
    if (d > 0 && sinTheta > 0) s.radianceOverPdf = texel(c.x, c.y) * (2 * kPi * kPi * sinTheta / d);
    return s;
  }
  // The texel a direction falls in, for unit-or-not d.
  void texelOf(const Vec3f& d, int& x, int& y) const {
    const float phi = std::atan2(d.x, -d.z) + rotation;  // 0 at the image's centre
    float u = phi * (0.5f / kPi) + 0.5f;
    u -= std::floor(u);
    const float len = length(d);
    const float cosTheta = len > 0 ? std::clamp(d.y / len, -1.0f, 1.0f) : 1.0f;
    const float v = std::acos(cosTheta) / kPi;
    x = std::clamp(static_cast<int>(u * static_cast<float>(image.width)), 0, image.width - 1);
    y = std::clamp(static_cast<int>(v * static_cast<float>(image.height)), 0, image.height - 1);
  }
};

EnvironmentLight::EnvironmentLight(const Rgb& radiance, int n) : samples(n), uniform_(radiance) {}

EnvironmentLight::EnvironmentLight(LatLongImage image, float intensity, float rotationDegrees,
                                   int n)
    : samples(n) {
  auto map = std::make_shared<Map>();
  const int w = image.width, h = image.height;
  map->image = std::move(image);
  for (Rgb& t : map->image.texels) t = t * intensity;
  map->rotation = rotationDegrees * (kPi / 180);
  map->rowCdf.resize(static_cast<size_t>(h) + 1);
  map->texelCdf.resize(static_cast<size_t>(h) * (static_cast<size_t>(w) + 1));
  map->density.assign(static_cast<size_t>(w) * static_cast<size_t>(h), 0.0f);
  // A texel's weight is its luminance times the solid angle its row spans per unit of v
  // (sin θ at the row's centre): bright texels, and texels nearer the horizon, which cover
  // more of the sphere, are drawn more often.
  std::vector<double> weight(static_cast<size_t>(w));
  std::vector<double> rowWeight(static_cast<size_t>(h));
  for (int y = 0; y < h; ++y) {
    const double sinTheta = std::sin(kPi * (y + 0.5) / h);
    for (int x = 0; x < w; ++x)
      weight[static_cast<size_t>(x)] = luminance(map->texel(x, y)) * sinTheta;
    rowWeight[static_cast<size_t>(y)] =
        cumulate(weight.data(), w, map->texelCdf.data() + static_cast<size_t>(y) * (w + 1));
  }
  const double total = cumulate(rowWeight.data(), h, map->rowCdf.data());
  map->rowBins = guideBinsFor(h);
  map->texelBins = guideBinsFor(w);
  map->rowGuide.resize(static_cast<size_t>(map->rowBins) + 1);
  map->texelGuide.resize(static_cast<size_t>(h) * (static_cast<size_t>(map->texelBins) + 1));
  GuidedCdf::buildGuide(map->rowCdf.data(), h, map->rowBins, map->rowGuide.data());
  for (int y = 0; y < h; ++y) {
    const auto row = static_cast<size_t>(y);
    GuidedCdf::buildGuide(map->texelCdf.data() + row * (static_cast<size_t>(w) + 1), w,
                          map->texelBins,
                          map->texelGuide.data() + row * (static_cast<size_t>(map->texelBins) + 1));
  }
  if (total > 0) {
    const double mean = total / (double(w) * double(h));
    for (int y = 0; y < h; ++y) {
      const double sinTheta = std::sin(kPi * (y + 0.5) / h);
      for (int x = 0; x < w; ++x)
        map->density[map->indexOf(x, y)] =
            static_cast<float>(luminance(map->texel(x, y)) * sinTheta / mean);
    }
  }
  map_ = std::move(map);
}

Rgb EnvironmentLight::radiance(const Vec3f& d) const {
  if (!map_) return uniform_;
  int x, y;
  map_->texelOf(d, x, y);
  return map_->texel(x, y);
}

EnvironmentSample EnvironmentLight::sample(const Vec3f& n, Vec2f u) const {
  if (!map_) return sampleUniform(n, u);
  return map_->sampleAt(map_->cellOf(u));
}

void EnvironmentLight::sample(const Vec3f& n, const Vec2f* u, int count,
                              EnvironmentSample* out) const {
  if (!map_) {
    for (int i = 0; i < count; ++i) out[i] = sampleUniform(n, u[i]);
    return;
  }
  // Every sample's cells first, then every sample's direction: a sample's table reads depend
  // on each other, and one sample at a time waited on each; side by side they overlap. The
  // arithmetic between the searches and the sines runs in lanes, with sampleAt's operations.
  const Map& m = *map_;
  const int w = m.image.width, h = m.image.height;
  // SSE's own width: GCC splits wider vectors' comparisons into single lanes.
  using F32x4 = float __attribute__((vector_size(16)));
  using I32x4 = int32_t __attribute__((vector_size(16)));
  constexpr int kLanes = 4, kBlock = 32;
  alignas(16) int xs[kBlock], ys[kBlock];
  alignas(16) float us[kBlock], vs[kBlock], rowLo[kBlock], rowHi[kBlock], texelLo[kBlock],
      texelHi[kBlock], theta[kBlock], phi[kBlock], sinTheta[kBlock], cosTheta[kBlock],
      sinPhi[kBlock], cosPhi[kBlock];
  const auto load = [](const auto* a) {
    using T = std::remove_cv_t<std::remove_pointer_t<decltype(a)>>;
    std::conditional_t<std::is_same_v<T, int>, I32x4, F32x4> v;
    std::memcpy(&v, a, sizeof v);
    return v;
  };
  const auto store = [](auto v, auto* a) { std::memcpy(a, &v, sizeof v); };
  for (int first = 0; first < count; first += kBlock) {
    const int size = std::min(kBlock, count - first);
    for (int i = 0; i < size; ++i) {
      const Vec2f ui = u[first + i];
      const int y = m.rows().cell(ui.y);
      const GuidedCdf texels = m.texelsOfRow(y);
      const int x = texels.cell(ui.x);
      const size_t at = m.indexOf(x, y);
      __builtin_prefetch(&m.density[at]);
      __builtin_prefetch(&m.image.texels[at]);
      xs[i] = x;
      ys[i] = y;
      us[i] = ui.x;
      vs[i] = ui.y;
      rowLo[i] = m.rowCdf[static_cast<size_t>(y)];
      rowHi[i] = m.rowCdf[static_cast<size_t>(y) + 1];
      texelLo[i] = texels.cdf[x];
      texelHi[i] = texels.cdf[x + 1];
    }
    // Lanes past the block's end hold any cell; their values are never read.
    const int lanes = (size + kLanes - 1) / kLanes * kLanes;
    for (int i = size; i < lanes; ++i) {
      xs[i] = ys[i] = 0;
      us[i] = vs[i] = rowLo[i] = texelLo[i] = 0;
      rowHi[i] = texelHi[i] = 1;
    }
    for (int i = 0; i < lanes; i += kLanes) {
      const F32x4 withinRow = GuidedCdf::within(load(vs + i), load(rowLo + i), load(rowHi + i));
      const F32x4 withinTexel =
          GuidedCdf::within(load(us + i), load(texelLo + i), load(texelHi + i));
      store(kPi * (convertLanes<F32x4>(load(ys + i)) + withinRow) / static_cast<float>(h),
            theta + i);
      store(2 * kPi *
                    ((convertLanes<F32x4>(load(xs + i)) + withinTexel) / static_cast<float>(w) -
                     0.5f) -
                m.rotation,
            phi + i);
    }
    // The sines and cosines in lanes too, the same floats as std::sin's and std::cos's: one
    // sample at a time they were a large part of a sky's samples.
    sinCos(theta, lanes, sinTheta, cosTheta);
    sinCos(phi, lanes, sinPhi, cosPhi);
    for (int i = 0; i < size; ++i) {
      EnvironmentSample& s = out[first + i];
      s.wi = {sinTheta[i] * sinPhi[i], cosTheta[i], -sinTheta[i] * cosPhi[i]};
      const size_t at = m.indexOf(xs[i], ys[i]);
      const float d = m.density[at];
      // The (u, v) square maps onto the sphere with dω = 2π² sin θ du dv (sampleAt).
      s.radianceOverPdf =
          d > 0 && sinTheta[i] > 0 ? m.image.texels[at] * (2 * kPi * kPi * sinTheta[i] / d) : Rgb{};
    }
  }
}

EnvironmentSample EnvironmentLight::sampleUniform(const Vec3f& n, Vec2f u) const {
  // Cosine-weighted about n: pdf cos θ/π, so L/pdf·cos θ is π·L whatever u is.
  EnvironmentSample s;
  const Vec2f disk = squareToDiskConcentric(u);
  const float z = std::sqrt(std::max(0.0f, 1 - disk.x * disk.x - disk.y * disk.y));
  Vec3f t, b;
  orthonormalBasis(n, t, b);
  s.wi = normalize(disk.x * t + disk.y * b + z * n);
  if (z > 0) s.radianceOverPdf = uniform_ * (kPi / z);
  return s;
}

float EnvironmentLight::pdf(const Vec3f& n, const Vec3f& d) const {
  if (!map_) return std::max(0.0f, dot(n, d)) / kPi;
  int x, y;
  map_->texelOf(d, x, y);
  const float sinTheta = std::sqrt(std::max(0.0f, 1 - d.y * d.y));
  if (!(sinTheta > 0)) return 0;
  return map_->density[static_cast<size_t>(y) * static_cast<size_t>(map_->image.width) +
                       static_cast<size_t>(x)] /
         (2 * kPi * kPi * sinTheta);
}

}  // namespace glint
