#pragma once
// The one sampler. Every number is keyed by (pixel, sample index, dimension, scene seed), so a
// frame is the same for any thread count, tile size or crop. Pixel samples are stratified;
// other dimensions (light, lens, time, gloss) draw from their own stratified sets, shuffled per
// pixel and dimension so they are not correlated with the pixel samples (seed 000 §13.4.2).
#include <cstdint>
#include <string_view>

#include "core/vec.h"

namespace glint {

// The most samples one pixel's set of one dimension may hold: the pixel's spp, or spp × an
// area light's samples. The sampler indexes a set in 32-bit arithmetic and places its points
// exactly only below 2^29 samples (sampler.cpp); no render could finish a pixel of more.
inline constexpr int64_t kMaxSampleSet = int64_t{1} << 28;

enum class SamplerKind {
  Regular,     // n×n cell centres (seed 000 §13.4.1 "regular"); non-square spp: see docs
  Random,      // independent uniform samples
  Stratified,  // jittered: one random point per stratum; correlated multi-jitter for any spp
  Sobol,       // Owen-scrambled Sobol (0,2)-sequence (Burley 2020): low discrepancy
};

std::string_view samplerName(SamplerKind);
bool parseSamplerKind(std::string_view name, SamplerKind& out);

// Dimensions are named, so adding an effect never shifts another effect's numbers. Effects that
// recur along a path (lights, gloss) take the bounce depth and an index into their key.
enum class Dim : uint32_t { Pixel = 0, Lens = 1, Time = 2, Light = 3, Gloss = 4 };

constexpr uint32_t dimension(Dim kind, int depth = 0, int index = 0) {
  return static_cast<uint32_t>(kind) | (static_cast<uint32_t>(depth) << 8) |
         (static_cast<uint32_t>(index) << 16);
}

// A render draws each pixel's samples as two halves from independent sample sets (each
// stratified, or each a scrambled sequence of its own): the difference of the two halves'
// means estimates the error of the pixel without the bias that stratification gives a sample
// variance (docs/validation.md, Error estimate). A render of n samples gives half 0 the first
// ceil(n/2) of them, half 1 the rest; kWholeSet is the pixel's one set of all its spp.
inline constexpr int kWholeSet = -1;
constexpr int halfSampleCount(int64_t samples, int half) {
  return static_cast<int>(half == 0 ? (samples + 1) / 2 : samples / 2);
}

// One dimension's sample set within one pixel: the hashes that depend only on (pixel,
// dimension, half), computed once and shared by every sample drawn from the set.
struct SamplePattern {
  uint64_t hash = 0;          // hashKey(seed, px, py, dim) (and the half): keys each jitter
  uint32_t scramble[3] = {};  // stratified: the permutation key; sobol: index, x, y scrambles
  uint32_t samples = 0;       // the camera samples the set is stratified over
  // A regular sampler's pixel dimension: cell centres. Regular grids are for pixel offsets
  // only; a regular render's other dimensions are stratified. Both halves share the one grid
  // of the pixel's spp cells: half h's sample j is cell 2j + h.
  bool cellCentres = false;
  uint32_t cellStride = 1, cellOffset = 0;
};

class Sampler {
 public:
  Sampler(SamplerKind kind, int samplesPerPixel, uint64_t seed)
      : kind_(kind), spp_(samplesPerPixel), seed_(seed) {}

  SamplerKind kind() const { return kind_; }
  int samplesPerPixel() const { return spp_; }

  // A sample is drawn in steps, each computed once for all that share it: the pixel's key
  // (the hash of seed and pixel), once per pixel; a dimension's pattern, which extends it by
  // one more step, once for all the samples drawn from it (e.g. once per light at a shading
  // point, not once per shadow sample).
  uint64_t pixelKey(int px, int py) const;
  // The set of `half` (0 or 1), or of the whole pixel (kWholeSet).
  SamplePattern pattern(uint64_t pixelKey, uint32_t dim, int half = kWholeSet) const;

  // Sample `index` in [0, pattern.samples) of the pattern's dimension, each coordinate in
  // [0, 1), stratified over the set's samples and over `count` sub-samples (e.g. shadow
  // samples per camera sample): flat index index·count + sub of a set of samples·count. For
  // the pixel dimension, the offset inside the pixel.
  Vec2f get2D(const SamplePattern& pattern, int index, int sub = 0, int count = 1) const;
  // get2D(pattern, index, firstSub + j, count) into out[j] for j in [0, size): the same
  // values, drawn side by side (sampler.cpp). Flat indices index·count + firstSub + j run on
  // across sub-samples into the next samples' (a run of a pixel's samples with count 1).
  void get2D(const SamplePattern& pattern, int index, int firstSub, int size, int count,
             Vec2f* out) const;
  // out[j] = get2D(*patterns[j], index, sub, count) for j in [0, size), where flat[j] = index·
  // count + sub: the same values, drawn side by side wherever the points lie and whichever
  // pixels' sets they come from (a light's samples at the points a chunk lights).
  void get2DAt(const SamplePattern* const* patterns, int count, const uint32_t* flat, int size,
               Vec2f* out) const;

 private:
  SamplerKind kind_;
  int spp_;
  uint64_t seed_;
};

// The lanes Sampler::get2D and get2DAt draw runs of points in: 16 where the CPU has AVX-512 (F,
// DQ and VL), else 8 (built for AVX2 and for baseline x86-64, chosen at load). Every width gives
// the same points.
int samplerLanes();
// For tests, which draw with every width this CPU runs: runs are drawn in `width` lanes from now
// on (set it while no other thread draws). False, changing nothing, for a width this CPU does
// not run.
bool setSamplerLanes(int width);

// Sub-samples [0, count) of each of n camera samples, sample k at index indices[k] of set
// *patterns[k], in that order (every sub-sample of the first sample, then of the next), drawn a
// window ahead with Sampler::get2DAt: one sample's few sub-samples (a light's shadow samples)
// fill a part of a block of lanes, several samples' fill it.
class SubSampleStream {
 public:
  static constexpr int kWindow = 64;
  SubSampleStream(const Sampler& sampler, int count, const SamplePattern* patterns,
                  const int* indices, int n)
      : sampler_(sampler), count_(count), patterns_(patterns), indices_(indices), n_(n) {}

  Vec2f next() {
    if (used_ == drawn_) refill();
    return window_[used_++];
  }

 private:
  void refill();

  const Sampler& sampler_;
  int count_;
  const SamplePattern* patterns_;
  const int* indices_;
  int n_;
  int sample_ = 0, sub_ = 0;  // the next to draw: sub-sample sub_ of sample sample_
  int drawn_ = 0, used_ = 0;
  Vec2f window_[kWindow];
};

// Which camera sample is being traced: keys every random number drawn along its paths.
struct SampleKey {
  SampleKey() = default;
  SampleKey(const Sampler* s, int x, int y, int i)
      : SampleKey(s, x, y, i, s ? s->pixelKey(x, y) : 0) {}
  // With the pixel's key computed once for all its samples (Sampler::pixelKey).
  SampleKey(const Sampler* s, int x, int y, int i, uint64_t key, int h = kWholeSet)
      : sampler(s), px(x), py(y), index(i), half(h), pixelKey(key) {}

  const Sampler* sampler = nullptr;
  int px = 0, py = 0, index = 0;  // index: within the half's set (or the whole set)
  int half = kWholeSet;
  uint64_t pixelKey = 0;

  // A dimension's pattern, for drawing several sub-samples of it (a light's shadow samples).
  SamplePattern pattern(uint32_t dim) const { return sampler->pattern(pixelKey, dim, half); }
  Vec2f get2D(const SamplePattern& pattern, int sub, int count) const {
    return sampler->get2D(pattern, index, sub, count);
  }
  // Sub-samples [firstSub, firstSub + size) of `count` at once, into out (Sampler::get2D).
  void get2D(const SamplePattern& pattern, int firstSub, int size, int count, Vec2f* out) const {
    sampler->get2D(pattern, index, firstSub, size, count, out);
  }
  Vec2f get2D(uint32_t dim, int sub = 0, int count = 1) const {
    return get2D(pattern(dim), sub, count);
  }
};

}  // namespace glint
