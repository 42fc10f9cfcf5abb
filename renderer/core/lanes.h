#pragma once
// Code written once for one value and for eight side by side. U names the 32-bit unsigned
// lanes: uint32_t for one, or eight in a GNU vector type (GCC and Clang share the extension;
// for baseline x86-64 a vector of eight 32-bit lanes is two SSE registers). Lanes<U> gives the
// matching float, double and 64-bit types; the helpers below are the few operations whose
// spelling differs between a scalar and a vector. The sampler draws its points with these
// (sampler.cpp). Everything here is inlined, so vectors never cross a call boundary, and GCC's
// note that vector arguments changed ABI in GCC 4.6 does not apply to any file that uses them.
#include <bit>
#include <cstdint>
#include <type_traits>

#pragma GCC diagnostic ignored "-Wpsabi"

namespace glint {

// Clang refuses [[gnu::vector_size]] on an alias; the __attribute__ spelling both accept.
using U32x8 = uint32_t __attribute__((vector_size(32)));
using I32x8 = int32_t __attribute__((vector_size(32)));
using F32x8 = float __attribute__((vector_size(32)));
using U64x8 = uint64_t __attribute__((vector_size(64)));
using F64x8 = double __attribute__((vector_size(64)));

template <class U>
struct Lanes;
template <>
struct Lanes<uint32_t> {
  static constexpr int kWidth = 1;
  using I32 = int32_t;
  using F32 = float;
  using U64 = uint64_t;
  using F64 = double;
};
template <>
struct Lanes<U32x8> {
  static constexpr int kWidth = 8;
  using I32 = I32x8;
  using F32 = F32x8;
  using U64 = U64x8;
  using F64 = F64x8;
};

// Each lane converted by value, as static_cast converts one.
template <class To, class From>
[[gnu::always_inline]] inline To convertLanes(From x) {
  if constexpr (std::is_arithmetic_v<From>)
    return static_cast<To>(x);
  else
    return __builtin_convertvector(x, To);
}

// All ones (−1) in the lanes where a comparison held, zero elsewhere, as integer lanes T. A
// scalar comparison gives a bool; a vector one already gives −1 or 0 per lane.
template <class T, class Comparison>
[[gnu::always_inline]] inline T laneMask(Comparison holds) {
  if constexpr (std::is_same_v<Comparison, bool>)
    return static_cast<T>(T{0} - static_cast<T>(holds));
  else
    return convertLanes<T>(holds);
}

// Whether any lane is nonzero.
[[gnu::always_inline]] inline bool anyLane(uint32_t x) { return x != 0; }
[[gnu::always_inline]] inline bool anyLane(U32x8 x) {
  using U64x4 = uint64_t __attribute__((vector_size(32)));
  const auto wide = std::bit_cast<U64x4>(x);
  return ((wide[0] | wide[1]) | (wide[2] | wide[3])) != 0;
}

}  // namespace glint
