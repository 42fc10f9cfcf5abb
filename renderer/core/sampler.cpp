#include "core/sampler.h"

#include <cmath>

#include "core/hash.h"

namespace glint {

namespace {

// Kensler's hashed permutation ("Correlated Multi-Jittered Sampling", Pixar 2013): a bijection
// on [0, len) chosen by `key`, computed in O(1) without storing a table.
uint32_t permute(uint32_t i, uint32_t len, uint32_t key) {
  uint32_t w = len - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= key;
    i *= 0xe170893d;
    i ^= key >> 16;
    i ^= (i & w) >> 4;
    i ^= key >> 8;
    i *= 0x0929eb3f;
    i ^= key >> 23;
    i ^= (i & w) >> 1;
    i *= 1 | key >> 27;
    i *= 0x6935fa69;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3;
    i ^= (i & w) >> 2;
    i *= 0xc860a3df;
    i &= w;
    i ^= i >> 5;
  } while (i >= len);
  return (i + key) % len;
}

uint32_t key32(uint64_t h) { return static_cast<uint32_t>(h ^ (h >> 32)); }

}  // namespace

std::string_view samplerName(SamplerKind k) {
  switch (k) {
    case SamplerKind::Regular:
      return "regular";
    case SamplerKind::Random:
      return "random";
    case SamplerKind::Stratified:
      return "stratified";
  }
  return "?";
}

bool parseSamplerKind(std::string_view name, SamplerKind& out) {
  for (auto k : {SamplerKind::Regular, SamplerKind::Random, SamplerKind::Stratified})
    if (samplerName(k) == name) {
      out = k;
      return true;
    }
  return false;
}

Vec2f Sampler::stratified2D(uint64_t pattern, int index, int n) const {
  // Correlated multi-jitter: an m×k grid with m·k ≥ n whose samples are also stratified in
  // each 1D projection; works for any n, not only squares.
  const auto N = static_cast<uint32_t>(n);
  const auto m = static_cast<uint32_t>(std::max(1.0, std::floor(std::sqrt(double(N)))));
  const uint32_t k = (N + m - 1) / m;
  const uint32_t p = key32(pattern);
  const uint32_t s = permute(static_cast<uint32_t>(index), N, p * 0x51633e2d);
  const uint32_t sx = permute(s % m, m, p * 0xa511e9b3);
  const uint32_t sy = permute(s / m, k, p * 0x63d83595);
  const float jx = toUnitFloat(hashKey(pattern, s, 1));
  const float jy = toUnitFloat(hashKey(pattern, s, 2));
  const float x = (static_cast<float>(s % m) + (static_cast<float>(sy) + jx) / float(k)) / float(m);
  const float y = (static_cast<float>(s / m) + (static_cast<float>(sx) + jy) / float(m)) / float(k);
  return {std::min(x, 0x1.fffffep-1f), std::min(y, 0x1.fffffep-1f)};
}

Vec2f Sampler::pixelSample(int px, int py, int index) const {
  const uint64_t pattern = hashKey(seed_, static_cast<uint32_t>(px), static_cast<uint32_t>(py),
                                   static_cast<uint32_t>(Dim::Pixel));
  switch (kind_) {
    case SamplerKind::Regular: {
      const int n = static_cast<int>(std::ceil(std::sqrt(double(spp_))));
      return {(static_cast<float>(index % n) + 0.5f) / float(n),
              (static_cast<float>(index / n) + 0.5f) / float(n)};
    }
    case SamplerKind::Random:
      return {toUnitFloat(hashKey(pattern, index, 1)), toUnitFloat(hashKey(pattern, index, 2))};
    case SamplerKind::Stratified:
      return stratified2D(pattern, index, spp_);
  }
  return {0.5f, 0.5f};
}

Vec2f Sampler::get2D(int px, int py, int index, uint32_t dim, int sub, int count) const {
  const uint64_t pattern =
      hashKey(seed_, static_cast<uint32_t>(px), static_cast<uint32_t>(py), dim);
  const int n = spp_ * count;
  // The shuffle: sample `index` of the pixel takes a permuted stratum of this dimension's set.
  const int flat = index * count + sub;
  if (kind_ == SamplerKind::Random)
    return {toUnitFloat(hashKey(pattern, flat, 1)), toUnitFloat(hashKey(pattern, flat, 2))};
  return stratified2D(pattern, flat, n);
}

}  // namespace glint
