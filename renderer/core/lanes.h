#pragma once
// Code written once for one value and for eight or sixteen side by side. U names the 32-bit
// unsigned lanes: uint32_t for one, or eight or sixteen in a GNU vector type (GCC and Clang share
// the extension; for baseline x86-64 a vector of eight 32-bit lanes is two SSE registers, and
// sixteen are meant for code built for AVX-512, where they are one register). Lanes<U> gives the
// matching float, double and 64-bit types; the helpers below are the few operations whose
// spelling differs between a scalar and a vector. The sampler draws its points with these
// (sampler.cpp). Everything here is inlined, so vectors never cross a call boundary, and GCC's
// note that vector arguments changed ABI in GCC 4.6 does not apply to any file that uses them.
#include <bit>
#include <cstdint>
#include <type_traits>

#pragma GCC diagnostic ignored "-Wpsabi"

namespace glint {

// N 32-bit lanes (8 or 16) in GNU vector types, and the signed, float, 64-bit and double
// lanes of as many. Typedefs: GCC 12 drops vector_size from an alias-declaration in a template
// (and Clang refuses [[gnu::vector_size]] there; the __attribute__ spelling both accept).
template <int N>
struct VectorLanes {
  static constexpr int kWidth = N;
  typedef uint32_t U32 __attribute__((vector_size(4 * N)));
  typedef int32_t I32 __attribute__((vector_size(4 * N)));
  typedef float F32 __attribute__((vector_size(4 * N)));
  typedef uint64_t U64 __attribute__((vector_size(8 * N)));
  typedef double F64 __attribute__((vector_size(8 * N)));
};
using U32x8 = VectorLanes<8>::U32;
using I32x8 = VectorLanes<8>::I32;
using F32x8 = VectorLanes<8>::F32;
using U64x8 = VectorLanes<8>::U64;
using F64x8 = VectorLanes<8>::F64;
using U32x16 = VectorLanes<16>::U32;
using I32x16 = VectorLanes<16>::I32;
using F32x16 = VectorLanes<16>::F32;
using U64x16 = VectorLanes<16>::U64;
using F64x16 = VectorLanes<16>::F64;
static_assert(sizeof(U32x8) == 32 && sizeof(F64x16) == 128);

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
struct Lanes<U32x8> : VectorLanes<8> {};
template <>
struct Lanes<U32x16> : VectorLanes<16> {};

// Sixteen 32-bit lanes widened to 64 bits half by half, in builds without optimisation only:
// there GCC 12 fails on the whole conversion for AVX-512 (an internal compiler error), and
// optimised, the halves' shuffles stay in the code.
#ifdef __OPTIMIZE__
inline constexpr bool kWidenInHalves = false;
#else
inline constexpr bool kWidenInHalves = true;
#endif
template <class To, class Half, class ToHalf, class From>
[[gnu::always_inline]] inline To widenInHalves(const From& x) {
  const Half low = __builtin_shufflevector(x, x, 0, 1, 2, 3, 4, 5, 6, 7);
  const Half high = __builtin_shufflevector(x, x, 8, 9, 10, 11, 12, 13, 14, 15);
  const ToHalf a = __builtin_convertvector(low, ToHalf), b = __builtin_convertvector(high, ToHalf);
  return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
// Each lane converted by value, as static_cast converts one.
template <class To, class From>
[[gnu::always_inline]] inline To convertLanes(From x) {
  if constexpr (std::is_arithmetic_v<From>)
    return static_cast<To>(x);
  else if constexpr (kWidenInHalves && std::is_same_v<From, U32x16> && std::is_same_v<To, U64x16>)
    return widenInHalves<To, U32x8, U64x8>(x);
  else if constexpr (kWidenInHalves && std::is_same_v<From, I32x16> && std::is_same_v<To, F64x16>)
    return widenInHalves<To, I32x8, F64x8>(x);
  else if constexpr (kWidenInHalves && std::is_same_v<From, F32x16> && std::is_same_v<To, F64x16>)
    return widenInHalves<To, F32x8, F64x8>(x);
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

// The bits of x as To, of x's size: std::bit_cast for one value; for lanes a GNU vector cast,
// which needs no call at any optimisation level (unoptimised, std::bit_cast of a vector is a
// call built for baseline x86-64, which an AVX clone passes its vectors wrongly).
template <class To, class From>
[[gnu::always_inline]] inline To laneBits(const From& x) {
  static_assert(sizeof(To) == sizeof(From));
  if constexpr (std::is_arithmetic_v<From>)
    return std::bit_cast<To>(x);
  else
    return (To)x;
}

// Whether any lane is nonzero.
[[gnu::always_inline]] inline bool anyLane(uint32_t x) { return x != 0; }
[[gnu::always_inline]] inline bool anyLane(U32x8 x) {
  using U64x4 = uint64_t __attribute__((vector_size(32)));
  const auto wide = laneBits<U64x4>(x);
  return ((wide[0] | wide[1]) | (wide[2] | wide[3])) != 0;
}
[[gnu::always_inline]] inline bool anyLane(U32x16 x) {
  const auto wide = laneBits<U64x8>(x);
  return (((wide[0] | wide[1]) | (wide[2] | wide[3])) |
          ((wide[4] | wide[5]) | (wide[6] | wide[7]))) != 0;
}

}  // namespace glint
