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

// One dimension's sample set within one pixel: the hashes that depend only on (pixel,
// dimension), computed once and shared by every sample drawn from the set.
struct SamplePattern {
  uint64_t hash = 0;          // hashKey(seed, px, py, dim): keys each sample's jitter
  uint32_t scramble[3] = {};  // stratified: the permutation key; sobol: index, x, y scrambles
};

// Test hook: power-of-two sets drawn with the portable build of the sampler's vector lanes
// even on a CPU with AVX2 (sampler.cpp), so that tests hold both builds to the same bits.
void forcePortableSamplerLanes(bool force);

class Sampler {
 public:
  Sampler(SamplerKind kind, int samplesPerPixel, uint64_t seed)
      : kind_(kind), spp_(samplesPerPixel), seed_(seed) {}

  SamplerKind kind() const { return kind_; }
  int samplesPerPixel() const { return spp_; }

  // Offset inside pixel (px, py) for sample `index` in [0, spp), each coordinate in [0, 1).
  Vec2f pixelSample(int px, int py, int index) const {
    return pixelSampleFor(pattern(pixelKey(px, py), dimension(Dim::Pixel)), index);
  }
  // A 2D sample of dimension `dim` for sample `index`, stratified over the spp samples of the
  // pixel and over `count` sub-samples (e.g. shadow samples per camera sample).
  Vec2f get2D(int px, int py, int index, uint32_t dim, int sub = 0, int count = 1) const {
    return get2DFor(pattern(pixelKey(px, py), dim), index, sub, count);
  }

  // The same in steps, for callers that draw many samples: the pixel's key (the hash of seed
  // and pixel), computed once per pixel; a dimension's pattern, which extends it by one more
  // step, computed once for all the samples drawn from it (e.g. once per light at a shading
  // point, not once per shadow sample). The values are exactly those above.
  uint64_t pixelKey(int px, int py) const;
  SamplePattern pattern(uint64_t pixelKey, uint32_t dim) const;
  Vec2f pixelSampleFor(const SamplePattern& pixel, int index) const;
  // pixelSampleFor for samples [first, first + size), into out.
  void pixelSamplesFor(const SamplePattern& pixel, int first, int size, Vec2f* out) const;
  // get2DFor(pattern, first + j) into out[j] for j in [0, size): a dimension drawn once per
  // sample (lens, time) for a run of one pixel's samples.
  void get2DRange(const SamplePattern& pattern, int first, int size, Vec2f* out) const {
    get2DFor(pattern, first, 0, size, 1, out);
  }
  Vec2f get2DFor(const SamplePattern& pattern, int index, int sub = 0, int count = 1) const;
  // get2DFor(pattern, index, firstSub + j, count) into out[j] for j in [0, size): the same
  // values, drawn side by side (for power-of-two sets in vector lanes, sampler.cpp). Flat
  // indices index·count + firstSub + j run on across sub-samples into the next samples'.
  void get2DFor(const SamplePattern& pattern, int index, int firstSub, int size, int count,
                Vec2f* out) const;

 private:
  static Vec2f stratified2D(const SamplePattern& pattern, int index, int n);
  static void stratified2D(const SamplePattern& pattern, int first, int size, int n, Vec2f* out);
  static Vec2f sobol2D(const SamplePattern& pattern, int index);

  SamplerKind kind_;
  int spp_;
  uint64_t seed_;
};

// Which camera sample is being traced: keys every random number drawn along its paths.
struct SampleKey {
  SampleKey() = default;
  SampleKey(const Sampler* s, int x, int y, int i)
      : SampleKey(s, x, y, i, s ? s->pixelKey(x, y) : 0) {}
  // With the pixel's key computed once for all its samples (Sampler::pixelKey).
  SampleKey(const Sampler* s, int x, int y, int i, uint64_t key)
      : sampler(s), px(x), py(y), index(i), pixelKey(key) {}

  const Sampler* sampler = nullptr;
  int px = 0, py = 0, index = 0;
  uint64_t pixelKey = 0;

  // A dimension's pattern, for drawing several sub-samples of it (a light's shadow samples).
  SamplePattern pattern(uint32_t dim) const { return sampler->pattern(pixelKey, dim); }
  Vec2f get2D(const SamplePattern& pattern, int sub, int count) const {
    return sampler->get2DFor(pattern, index, sub, count);
  }
  // Sub-samples [firstSub, firstSub + size) of `count` at once, into out.
  void get2D(const SamplePattern& pattern, int firstSub, int size, int count, Vec2f* out) const {
    sampler->get2DFor(pattern, index, firstSub, size, count, out);
  }
  Vec2f get2D(uint32_t dim, int sub = 0, int count = 1) const {
    return get2D(pattern(dim), sub, count);
  }
};

}  // namespace glint
