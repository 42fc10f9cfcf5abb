#pragma once
// Stateless integer hashing: every random number in Glint is a pure function of its key, never
// of a thread or of how many numbers were drawn before it.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace glint {

// SplitMix64's finaliser (Steele, Lea, Flood 2014): full avalanche on 64 bits. U64 is uint64_t
// or a vector of them (GNU vector extensions: the sampler hashes lanes side by side).
template <class U64>
[[gnu::always_inline]] constexpr U64 mix64Lanes(U64 z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
constexpr uint64_t mix64(uint64_t z) { return mix64Lanes(z); }

// hashCombine's terms that depend only on the seed: hoisted where one seed hashes many values.
// In lanes too, as mix64Lanes (the sampler's lanes may each have a seed of their own).
template <class U64>
[[gnu::always_inline]] constexpr U64 hashCombineOffsetLanes(U64 seed) {
  return 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
}
constexpr uint64_t hashCombineOffset(uint64_t seed) { return hashCombineOffsetLanes(seed); }

constexpr uint64_t hashCombine(uint64_t seed, uint64_t v) {
  return mix64(seed ^ (v + hashCombineOffset(seed)));
}

template <typename... Ts>
constexpr uint64_t hashKey(uint64_t first, Ts... rest) {
  uint64_t h = mix64(first + 0x9e3779b97f4a7c15ULL);
  ((h = hashCombine(h, static_cast<uint64_t>(rest))), ...);
  return h;
}

// FNV-1a over bytes, finished with mix64: a content hash (scene files, settings).
inline uint64_t hashBytes(std::string_view bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return mix64(h);
}

// Top 24 bits as a float in [0, 1): exactly representable, never 1.
constexpr float toUnitFloat(uint64_t bits) {
  return static_cast<float>(bits >> 40) * (1.0f / 16777216.0f);
}

// A hash as the 16 lower-case hex digits frames and manifests carry it as.
inline std::string hexDigits(uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace glint
