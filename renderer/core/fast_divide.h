#pragma once
// Quotient and remainder by a divisor fixed at run time, with multiplications instead of a
// divide instruction (Lemire, Kaser, Kurz, "Faster Remainder by Direct Computation", 2019):
// exact for every 32-bit dividend. The stratified sampler divides by the same few counts (the
// samples of a set, the sides of its grid) for every point it draws, one at a time or in
// lanes (core/lanes.h): U is uint32_t or lanes of them, and each lane gets the same bits.
#include <bit>
#include <cstdint>

#include "core/lanes.h"

namespace glint {

class FastDivisor {
 public:
  FastDivisor() = default;
  // M = ⌈2^64 / d⌉. A power of two (1 included, which would need M = 2^64) divides by a shift:
  // most sets are powers of two (spp, light samples), and a shift is a fraction of the products
  // (and needs no M, whose division a set drawn for one point paid for).
  explicit FastDivisor(uint32_t d)
      : d_(d),
        m_(d == 0 || isPowerOfTwo(d) ? 0 : UINT64_MAX / d + 1),
        shift_(isPowerOfTwo(d) ? std::countr_zero(d) : -1) {}

  // std::has_single_bit, which baseline x86-64 (no POPCNT) calls out to libgcc for.
  static constexpr bool isPowerOfTwo(uint32_t d) { return d != 0 && (d & (d - 1)) == 0; }

  uint32_t divisor() const { return d_; }

  template <class U>
  [[gnu::always_inline]] U quotient(U a) const {
    if (shift_ >= 0) return a >> static_cast<uint32_t>(shift_);
    return convertLanes<U>(mulHigh(m_, widen(a)));
  }
  template <class U>
  [[gnu::always_inline]] U remainder(U a) const {
    if (shift_ >= 0) return a & (d_ - 1);
    return convertLanes<U>(mulHigh(m_ * widen(a), d_));  // the fraction a/d, times d
  }

 private:
  // The high 64 bits of x·y for y < 2^32, from two 32 × 32 → 64-bit products (a vector unit
  // has no wider multiply): x·y = x_hi·y·2^32 + x_lo·y, and x_hi·y + ⌊x_lo·y / 2^32⌋ cannot
  // overflow 64 bits. Either side may be one value for all lanes.
  template <class X, class Y>
  [[gnu::always_inline]] static auto mulHigh(X x, Y y) {
    return ((x >> 32) * y + ((x & 0xffffffffu) * y >> 32)) >> 32;
  }
  template <class U>
  [[gnu::always_inline]] static auto widen(U a) {
    return convertLanes<typename Lanes<U>::U64>(a);
  }

  uint32_t d_ = 1;
  uint64_t m_ = 0;
  int shift_ = 0;  // log2 d for a power of two, else −1
};

}  // namespace glint
