#pragma once
// Quotient and remainder by a divisor fixed at run time, with multiplications instead of a
// divide instruction (Lemire, Kaser, Kurz, "Faster Remainder by Direct Computation", 2019):
// exact for every 32-bit dividend. The stratified sampler divides by the same few counts (the
// samples of a set, the sides of its grid) millions of times per frame.
#include <cstdint>

namespace glint {

class FastDivisor {
 public:
  FastDivisor() = default;
  // M = ⌈2^64 / d⌉; d = 1 would need 2^64, so it keeps M = 0 and takes the quotient as is.
  explicit FastDivisor(uint32_t d) : d_(d), m_(d > 1 ? UINT64_MAX / d + 1 : 0) {}

  uint32_t divisor() const { return d_; }
  uint32_t quotient(uint32_t a) const {
    return d_ == 1 ? a : static_cast<uint32_t>(mulHigh(m_, a));
  }
  uint32_t remainder(uint32_t a) const {
    return static_cast<uint32_t>(mulHigh(m_ * a, d_));  // the fraction a/d, times d
  }

 private:
  __extension__ using U128 = unsigned __int128;
  static uint64_t mulHigh(uint64_t a, uint64_t b) {
    return static_cast<uint64_t>((static_cast<U128>(a) * b) >> 64);
  }

  uint32_t d_ = 1;
  uint64_t m_ = 0;
};

}  // namespace glint
