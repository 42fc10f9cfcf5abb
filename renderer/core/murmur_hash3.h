#pragma once
// MurmurHash3_x86_32 (Austin Appleby, SMHasher, public domain): the hash that Cryptomatte names
// its IDs with (film/cryptomatte.h). Written from the reference MurmurHash3.cpp; blocks are read
// little-endian, as the reference reads them on x86, so the value is the same on every host.
#include <cstdint>
#include <string_view>

namespace glint {

constexpr uint32_t murmurHash3_x86_32(std::string_view key, uint32_t seed = 0) {
  constexpr uint32_t c1 = 0xcc9e2d51, c2 = 0x1b873593;
  const auto rotl = [](uint32_t x, int r) { return (x << r) | (x >> (32 - r)); };
  const auto byte = [&](size_t i) { return uint32_t(static_cast<unsigned char>(key[i])); };
  const auto scramble = [&](uint32_t k) { return rotl(k * c1, 15) * c2; };
  const size_t blocks = key.size() / 4;
  uint32_t h = seed;
  for (size_t b = 0; b < blocks; ++b) {
    const size_t i = 4 * b;
    h ^= scramble(byte(i) | byte(i + 1) << 8 | byte(i + 2) << 16 | byte(i + 3) << 24);
    h = rotl(h, 13) * 5 + 0xe6546b64;
  }
  // The 1–3 bytes left over, as the reference's fall-through switch.
  uint32_t tail = 0;
  for (size_t i = key.size(); i-- > 4 * blocks;) tail = tail << 8 | byte(i);
  if (key.size() % 4 != 0) h ^= scramble(tail);
  // The reference hashes an int length: its low 32 bits.
  h ^= static_cast<uint32_t>(key.size());
  // fmix32: every input bit reaches every output bit.
  h ^= h >> 16;
  h *= 0x85ebca6b;
  h ^= h >> 13;
  h *= 0xc2b2ae35;
  h ^= h >> 16;
  return h;
}

}  // namespace glint
