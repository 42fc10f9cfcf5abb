#include "lights/environment.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "core/cpu_features.h"
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
  // Their guides (lights/guided_cdf.h), which start each of a sample's two binary searches
  // near its answer.
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
  // Whether cellsInLanes may run: AVX2's gathers, and every table index an int.
  bool searchesInLanes() const;
  // cellOf's x and y, and the bounds of each cell's row and texel in the tables, for the
  // samples (us[i], vs[i]), i in [0, count), count a multiple of 8·kSearchGroups: that many
  // groups of eight searches side by side.
  static constexpr int kSearchGroups = 2;
  void cellsInLanes(const float* us, const float* vs, int count, int* xs, int* ys, float* rowLo,
                    float* rowHi, float* texelLo, float* texelHi) const;
};

namespace {

// std::upper_bound of u over table[base + lo, base + hi) in each of eight lanes of each of G
// groups, as the index (from base) of the first entry above u, or hi: the same steps, each lane
// going on while its range is not empty. The groups step side by side: each step's gathers wait
// on the step before, and one group alone left the core waiting on them.
template <int G>
[[gnu::target("avx2")]] inline void upperBoundLanes(const float* table, const __m256i* base,
                                                    __m256i* lo, const __m256i* hi,
                                                    const __m256* u) {
  const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
  __m256i len[G], active[G];
  for (int g = 0; g < G; ++g) len[g] = _mm256_sub_epi32(hi[g], lo[g]);
  for (;;) {
    __m256i any = zero;
    for (int g = 0; g < G; ++g) {
      active[g] = _mm256_cmpgt_epi32(len[g], zero);
      any = _mm256_or_si256(any, active[g]);
    }
    if (_mm256_testz_si256(any, any)) return;
    for (int g = 0; g < G; ++g) {
      const __m256i half = _mm256_srli_epi32(len[g], 1);
      const __m256i middle = _mm256_add_epi32(lo[g], half);
      const __m256 at =
          _mm256_mask_i32gather_ps(_mm256_setzero_ps(), table, _mm256_add_epi32(base[g], middle),
                                   _mm256_castsi256_ps(active[g]), 4);
      // upper_bound's step: past the middle unless u < *middle.
      const __m256i past =
          _mm256_andnot_si256(_mm256_castps_si256(_mm256_cmp_ps(u[g], at, _CMP_LT_OQ)), active[g]);
      lo[g] = _mm256_blendv_epi8(lo[g], _mm256_add_epi32(middle, one), past);
      len[g] =
          _mm256_blendv_epi8(half, _mm256_sub_epi32(_mm256_sub_epi32(len[g], half), one), past);
    }
  }
}

// GuidedCdf::cell's clamp of the index found into [0, n).
[[gnu::target("avx2")]] inline __m256i cellLanes(__m256i above, int n) {
  return _mm256_min_epi32(
      _mm256_max_epi32(_mm256_sub_epi32(above, _mm256_set1_epi32(1)), _mm256_setzero_si256()),
      _mm256_set1_epi32(n - 1));
}

// All ones where x is in [0, 1).
[[gnu::target("avx2")]] inline __m256i inUnitLanes(__m256 x) {
  return _mm256_castps_si256(_mm256_and_ps(_mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_GE_OQ),
                                           _mm256_cmp_ps(x, _mm256_set1_ps(1), _CMP_LT_OQ)));
}

// GuidedCdf::cell's guide bin of x, 0 outside `valid`.
[[gnu::target("avx2")]] inline __m256i binLanes(__m256 x, int bins, __m256i valid) {
  return _mm256_and_si256(
      _mm256_cvttps_epi32(_mm256_mul_ps(x, _mm256_set1_ps(static_cast<float>(bins)))), valid);
}

}  // namespace

bool EnvironmentLight::Map::searchesInLanes() const {
  return cpuFeatures().avx2 && double(image.height) * (double(image.width) + 1) < 0x1p31 &&
         double(image.height) * (double(texelBins) + 1) < 0x1p31;
}

[[gnu::target("avx2")]] void EnvironmentLight::Map::cellsInLanes(const float* us, const float* vs,
                                                                 int count, int* xs, int* ys,
                                                                 float* rowLo, float* rowHi,
                                                                 float* texelLo,
                                                                 float* texelHi) const {
  constexpr int G = kSearchGroups;
  const int w = image.width, h = image.height;
  const __m256i one = _mm256_set1_epi32(1);
  const auto* rowGuideData = reinterpret_cast<const int*>(rowGuide.data());
  const auto* texelGuideData = reinterpret_cast<const int*>(texelGuide.data());
  for (int first = 0; first < count; first += 8 * G) {
    __m256 u[G], v[G];
    __m256i valid[G], base[G], lo[G], hi[G], y[G], x[G];
    // The guide serves u in [0, 1) (GuidedCdf::cell); other lanes search from bin 0 here and
    // are searched again one at a time below.
    for (int g = 0; g < G; ++g) {
      u[g] = _mm256_loadu_ps(us + first + 8 * g);
      v[g] = _mm256_loadu_ps(vs + first + 8 * g);
      valid[g] = _mm256_and_si256(inUnitLanes(u[g]), inUnitLanes(v[g]));
      const __m256i rowBin = binLanes(v[g], rowBins, valid[g]);
      base[g] = _mm256_setzero_si256();
      lo[g] = _mm256_i32gather_epi32(rowGuideData, rowBin, 4);
      hi[g] = _mm256_i32gather_epi32(rowGuideData, _mm256_add_epi32(rowBin, one), 4);
    }
    upperBoundLanes<G>(rowCdf.data(), base, lo, hi, v);
    for (int g = 0; g < G; ++g) {
      y[g] = cellLanes(lo[g], h);
      base[g] = _mm256_mullo_epi32(y[g], _mm256_set1_epi32(w + 1));
      const __m256i guideAt =
          _mm256_add_epi32(_mm256_mullo_epi32(y[g], _mm256_set1_epi32(texelBins + 1)),
                           binLanes(u[g], texelBins, valid[g]));
      lo[g] = _mm256_i32gather_epi32(texelGuideData, guideAt, 4);
      hi[g] = _mm256_i32gather_epi32(texelGuideData, _mm256_add_epi32(guideAt, one), 4);
    }
    upperBoundLanes<G>(texelCdf.data(), base, lo, hi, u);
    for (int g = 0; g < G; ++g) {
      const int i = first + 8 * g;
      x[g] = cellLanes(lo[g], w);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(xs + i), x[g]);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(ys + i), y[g]);
      _mm256_storeu_ps(rowLo + i, _mm256_i32gather_ps(rowCdf.data(), y[g], 4));
      _mm256_storeu_ps(rowHi + i,
                       _mm256_i32gather_ps(rowCdf.data(), _mm256_add_epi32(y[g], one), 4));
      const __m256i texelAt = _mm256_add_epi32(base[g], x[g]);
      _mm256_storeu_ps(texelLo + i, _mm256_i32gather_ps(texelCdf.data(), texelAt, 4));
      _mm256_storeu_ps(texelHi + i,
                       _mm256_i32gather_ps(texelCdf.data(), _mm256_add_epi32(texelAt, one), 4));
      for (int invalid = ~_mm256_movemask_ps(_mm256_castsi256_ps(valid[g])) & 0xff; invalid != 0;
           invalid &= invalid - 1) {
        const int k = i + __builtin_ctz(static_cast<unsigned>(invalid));
        ys[k] = rows().cell(vs[k]);
        const GuidedCdf texels = texelsOfRow(ys[k]);
        xs[k] = texels.cell(us[k]);
        rowLo[k] = rowCdf[static_cast<size_t>(ys[k])];
        rowHi[k] = rowCdf[static_cast<size_t>(ys[k]) + 1];
        texelLo[k] = texels.cdf[xs[k]];
        texelHi[k] = texels.cdf[xs[k] + 1];
      }
    }
  }
}

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
  const bool searchInLanes = m.searchesInLanes();
  for (int first = 0; first < count; first += kBlock) {
    const int size = std::min(kBlock, count - first);
    // Lanes past the block's end hold any cell; their values are never read.
    const int lanes = (size + kLanes - 1) / kLanes * kLanes;
    if (searchInLanes) {
      // Sixteen searches side by side: one at a time, their branches and dependent loads were
      // the largest part of a sample after its sines.
      constexpr int kSearched = 8 * Map::kSearchGroups;
      static_assert(kBlock % kSearched == 0);
      const int searched = (size + kSearched - 1) / kSearched * kSearched;
      for (int i = 0; i < size; ++i) us[i] = u[first + i].x, vs[i] = u[first + i].y;
      for (int i = size; i < searched; ++i) us[i] = vs[i] = 0;
      m.cellsInLanes(us, vs, searched, xs, ys, rowLo, rowHi, texelLo, texelHi);
      for (int i = 0; i < size; ++i) {
        const size_t at = m.indexOf(xs[i], ys[i]);
        __builtin_prefetch(&m.density[at]);
        __builtin_prefetch(&m.image.texels[at]);
      }
    } else {
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
      for (int i = size; i < lanes; ++i) {
        xs[i] = ys[i] = 0;
        us[i] = vs[i] = rowLo[i] = texelLo[i] = 0;
        rowHi[i] = texelHi[i] = 1;
      }
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
    // The sines and cosines in lanes too, the same floats as std::sin's and std::cos's: each
    // sample needs two of each.
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
