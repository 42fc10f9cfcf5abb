// The constructions are written once, as templates over the lanes U of core/lanes.h:
// uint32_t draws one point, U32x8 eight and U32x16 sixteen side by side, and all give the same
// bits (Sampler.LanesMatchOnePointAtATime).
#include "core/sampler.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/avx2_clones.h"
#include "core/cpu_features.h"
#include "core/fast_divide.h"
#include "core/hash.h"
#include "core/lanes.h"

namespace glint {

namespace {

// The set [0, len) that a permutation shuffles, with what permute() needs of it precomputed.
struct PermutationDomain {
  explicit PermutationDomain(uint32_t len) : size(len), mask(len - 1) {
    mask |= mask >> 1;  // the smallest all-ones mask covering len - 1
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
  }
  FastDivisor size;
  uint32_t mask;
};

// One round of permute()'s hash; `w` masks it to the domain's bit width. K: one key for every
// lane (uint32_t), or a key per lane (U).
template <class U, class K>
[[gnu::always_inline]] inline U permuteRound(U i, uint32_t w, K key) {
  i ^= key;
  i *= 0xe170893du;
  i ^= key >> 16;
  i ^= (i & w) >> 4;
  i ^= key >> 8;
  i *= 0x0929eb3fu;
  i ^= key >> 23;
  i ^= (i & w) >> 1;
  i *= 1u | key >> 27;
  i *= 0x6935fa69u;
  i ^= (i & w) >> 11;
  i *= 0x74dcb303u;
  i ^= (i & w) >> 2;
  i *= 0x9e501cc3u;
  i ^= (i & w) >> 2;
  i *= 0xc860a3dfu;
  i &= w;
  i ^= i >> 5;
  return i;
}

// Kensler's hashed permutation ("Correlated Multi-Jittered Sampling", Pixar 2013): a bijection
// on [0, len) chosen by `key`, computed in O(1) without storing a table. Rounds repeat until
// the value falls inside the domain (cycle walking); in lanes, only in the lanes still outside
// it. For len = 2^b a round never leaves the domain (its last steps mask i to w and shift bits
// down), so there is one round.
template <class U, class K>
[[gnu::always_inline]] inline U permute(U i, const PermutationDomain& domain, K key) {
  const uint32_t len = domain.size.divisor();
  i = permuteRound(i, domain.mask, key);
  for (U outside = laneMask<U>(i >= len); anyLane(outside); outside = laneMask<U>(i >= len))
    i ^= (permuteRound(i, domain.mask, key) ^ i) & outside;
  return domain.size.remainder(i + key);
}

// The points of lanes x and y, the first `size` lanes, into out.
template <class U>
[[gnu::always_inline]] inline void storePoints(typename Lanes<U>::F32 x, typename Lanes<U>::F32 y,
                                               int size, Vec2f* out) {
  if constexpr (Lanes<U>::kWidth == 1) {
    out[0] = {x, y};
  } else if (size < Lanes<U>::kWidth) {
    for (int l = 0; l < size; ++l) out[l] = {x[l], y[l]};
  } else if constexpr (Lanes<U>::kWidth == 8) {
    // Two interleaves of eight: GCC builds one of sixteen through the stack a float at a time,
    // and the stores' reloads wait on it (store forwarding).
    const F32x8 low = __builtin_shufflevector(x, y, 0, 8, 1, 9, 2, 10, 3, 11);
    const F32x8 high = __builtin_shufflevector(x, y, 4, 12, 5, 13, 6, 14, 7, 15);
    std::memcpy(static_cast<void*>(out), &low, sizeof low);
    std::memcpy(static_cast<void*>(out + 4), &high, sizeof high);
  } else {
    const F32x16 low =
        __builtin_shufflevector(x, y, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
    const F32x16 high =
        __builtin_shufflevector(x, y, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
    std::memcpy(static_cast<void*>(out), &low, sizeof low);
    std::memcpy(static_cast<void*>(out + 8), &high, sizeof high);
  }
}

// The m × k grid of a correlated multi-jittered set of n = m·k points (Kensler 2013): m is the
// largest divisor of n not above √n, so every cell holds one point for any n (a prime n gives
// a 1 × n grid, still n-rooks): a grid with m·k > n would leave the same cells empty in every
// pixel, a bias no spp removes.
struct JitterGrid {
  explicit JitterGrid(uint32_t n)
      : all(n),
        columns(largestDivisorUpToRoot(n)),
        rows(n / columns.size.divisor()),
        count(n),
        inverseCount(1.0 / n) {}
  static uint32_t largestDivisorUpToRoot(uint32_t n) {
    // 2^⌊b/2⌋ for n = 2^b, without the root and the trial divisions (most sets are powers of two).
    if (FastDivisor::isPowerOfTwo(n)) return 1u << (std::bit_width(n) - 1) / 2;
    auto m = static_cast<uint32_t>(std::max(1.0, std::floor(std::sqrt(double(n)))));
    while (n % m != 0) --m;
    return m;
  }
  PermutationDomain all, columns, rows;
  double count, inverseCount;
};

// What a point's draw reads of its pattern: one pattern's, the same in every lane (K = uint32_t,
// K64 = uint64_t), or each lane's own (K = U32x8 or U32x16, K64 = U64x8 or U64x16: a block of
// points drawn from several pixels' sets of one size).
template <class K, class K64>
struct PatternLanes {
  K scramble[3];
  K64 hash;
};
PatternLanes<uint32_t, uint64_t> lanesOf(const SamplePattern& p) {
  return {{p.scramble[0], p.scramble[1], p.scramble[2]}, p.hash};
}
// Lane l of block U from *patterns[l].
template <class U>
[[gnu::always_inline]] inline PatternLanes<U, typename Lanes<U>::U64> lanesOf(
    const SamplePattern* const* patterns) {
  PatternLanes<U, typename Lanes<U>::U64> p;
  for (int l = 0; l < Lanes<U>::kWidth; ++l) {
    for (int c = 0; c < 3; ++c) p.scramble[c][l] = patterns[l]->scramble[c];
    p.hash[l] = patterns[l]->hash;
  }
  return p;
}

// One correlated multi-jittered set: a pixel's dimension, drawn on the grid of its n points.
// Each point is placed in its cell so that both 1D projections are stratified too (n-rooks).
class StratifiedSet {
 public:
  explicit StratifiedSet(uint32_t n) : grid_(n) {}

  // The points at the set's indices `index` (lanes) of the pattern(s) `p`, the first `size`
  // lanes into out.
  template <class U, class K, class K64>
  [[gnu::always_inline]] void draw(U index, const PatternLanes<K, K64>& p, int size,
                                   Vec2f* out) const {
    using L = Lanes<U>;
    const K allKey = p.scramble[0] * 0x51633e2du, columnKey = p.scramble[0] * 0xa511e9b3u,
            rowKey = p.scramble[0] * 0x63d83595u;
    const uint32_t m = grid_.columns.size.divisor(), k = grid_.rows.size.divisor();
    const U s = permute(index, grid_.all, allKey);
    const U row = grid_.columns.size.quotient(s), column = s - row * m;
    const U sx = permute(column, grid_.columns, columnKey);
    const U sy = permute(row, grid_.rows, rowKey);
    // Both jitters from one hash: hashCombine(hash, s), as unitPair takes them.
    const typename L::U64 bits =
        mix64Lanes(p.hash ^ (convertLanes<typename L::U64>(s) + hashCombineOffsetLanes(p.hash)));
    // The point sits in cell (column, row) of the coarse grid and, inside it, in sub-cell
    // (sy, sx) of the fine n × n grid: stratum column·k + sy of n along x, row·m + sx along y.
    const double count = grid_.count, inverseCount = grid_.inverseCount;
    storePoints<U>(place<U>(column * k + sy, bits >> 40, count, inverseCount),
                   place<U>(row * m + sx, (bits & 0xffffffffu) >> 8, count, inverseCount), size,
                   out);
  }

 private:
  // (stratum + jitter) / n as a float inside [stratum, stratum + 1) / n, for a jitter of 24
  // bits (jitter24 · 2^-24). The sum is exact in double; rounding the quotient to float can
  // cross the stratum's lower edge when the jitter is within a float ulp of 0, or reach the
  // next stratum's edge when it is within one of 1: such a value steps one ulp back inside
  // (x·n is exact in double for n < 2^29; x ≥ 0 there, so the float one ulp up or down is the
  // bit pattern plus or minus one). Strata (below 2^28) and jitters (2^24) convert through
  // signed lanes, which SSE converts to double in one instruction; the edge tests read the
  // sign of a difference of integers-valued doubles, which SSE2 has no lane compare for.
  template <class U, class U64>
  [[gnu::always_inline]] typename Lanes<U>::F32 place(U stratum, U64 jitter24, double count,
                                                      double inverseCount) const {
    using L = Lanes<U>;
    using I32 = typename L::I32;
    const auto low = convertLanes<typename L::F64>(convertLanes<I32>(stratum));
    const auto jitter =
        convertLanes<typename L::F64>(convertLanes<I32>(jitter24)) * (1.0 / 16777216.0);
    const auto x = convertLanes<typename L::F32>((low + jitter) * inverseCount);
    const auto scaled = convertLanes<typename L::F64>(x) * count;
    const auto below = laneBits<typename L::U64>(scaled - low) >> 63;           // 1: below
    const auto inside = laneBits<typename L::U64>(scaled - (low + 1.0)) >> 63;  // 1: inside
    const I32 bits = laneBits<I32>(x) + convertLanes<I32>(below) - (1 - convertLanes<I32>(inside));
    return laneBits<typename L::F32>(bits);
  }

  JitterGrid grid_;
};

template <class U>
[[gnu::always_inline]] inline U reverseBits(U x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  return x;
}

// Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020): a Laine–Karras style hash that
// only lets higher bits depend on lower ones, applied to the bit-reversed value, is a nested
// uniform (Owen) scramble: it randomises the points and keeps every elementary interval full.
template <class U, class K>
[[gnu::always_inline]] inline U nestedUniformScramble(U x, K seed) {
  x = reverseBits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverseBits(x);
}

// The first two Sobol dimensions form a (0,2)-sequence in base 2: the van der Corput radical
// inverse (reverseBits), and the sequence generated by the Pascal matrix mod 2.
template <class U>
[[gnu::always_inline]] inline U sobolDimension1(U i) {
  U r{};
  for (uint32_t v = 1u << 31; anyLane(i); i >>= 1u, v ^= v >> 1) r ^= v & (0u - (i & 1u));
  return r;
}

// The top 24 bits as a float in [0, 1); they convert exactly through signed lanes.
template <class U>
[[gnu::always_inline]] inline typename Lanes<U>::F32 bitsToUnit(U bits) {
  using L = Lanes<U>;
  return convertLanes<typename L::F32>(convertLanes<typename L::I32>(bits >> 8u)) *
         (1.0f / 16777216.0f);
}

// Owen-scrambled Sobol points at the set's indices `index` (lanes), the first `size` into out.
// The index is Owen-scrambled too, which shuffles the order of the sequence per pattern while
// every power-of-two prefix stays a (0,m,2)-net.
template <class U, class K, class K64>
[[gnu::always_inline]] inline void sobol2D(const PatternLanes<K, K64>& p, U index, int size,
                                           Vec2f* out) {
  const U i = nestedUniformScramble(index, p.scramble[0]);
  const U x = nestedUniformScramble(reverseBits(i), p.scramble[1]);
  const U y = nestedUniformScramble(sobolDimension1(i), p.scramble[2]);
  storePoints<U>(bitsToUnit(x), bitsToUnit(y), size, out);
}

// Where a run's points sit: at one pattern's flat indices first, first + 1, ...
class RangeRun {
 public:
  RangeRun(const SamplePattern& pattern, uint32_t first)
      : lanes_(lanesOf(pattern)), first_(first) {}
  uint32_t index(int j) const { return first_ + static_cast<uint32_t>(j); }
  template <class U>
  [[gnu::always_inline]] U indexBlock(int j) const {
    U index;
    for (int l = 0; l < Lanes<U>::kWidth; ++l) index[l] = static_cast<uint32_t>(l);
    return this->index(j) + index;
  }
  const PatternLanes<uint32_t, uint64_t>& patternAt(int) const { return lanes_; }
  template <class U>
  [[gnu::always_inline]] const PatternLanes<uint32_t, uint64_t>& patternBlock(int, int) const {
    return lanes_;
  }

 private:
  PatternLanes<uint32_t, uint64_t> lanes_;
  uint32_t first_;
};
// ... or at flat index flat[j] of *patterns[j], the patterns' sets all of one size.
class ListRun {
 public:
  ListRun(const SamplePattern* const* patterns, const uint32_t* flat)
      : patterns_(patterns), flat_(flat) {}
  uint32_t index(int j) const { return flat_[j]; }
  template <class U>
  [[gnu::always_inline]] U indexBlock(int j) const {
    U index;
    std::memcpy(&index, flat_ + j, sizeof index);
    return index;
  }
  PatternLanes<uint32_t, uint64_t> patternAt(int j) const { return lanesOf(*patterns_[j]); }
  // The lanes of block U from j on, those at or past `size` repeating point size − 1.
  template <class U>
  [[gnu::always_inline]] PatternLanes<U, typename Lanes<U>::U64> patternBlock(int j,
                                                                              int size) const {
    constexpr int kWidth = Lanes<U>::kWidth;
    if (j + kWidth <= size) return lanesOf<U>(patterns_ + j);
    const SamplePattern* tail[kWidth];
    for (int l = 0; l < kWidth; ++l) tail[l] = patterns_[std::min(j + l, size - 1)];
    return lanesOf<U>(tail);
  }

 private:
  const SamplePattern* const* patterns_;
  const uint32_t* flat_;
};

// A run seen from its point `from` on.
template <class Run>
struct Offset {
  const Run& run;
  int from;
  uint32_t index(int j) const { return run.index(from + j); }
  template <class U>
  [[gnu::always_inline]] U indexBlock(int j) const {
    return run.template indexBlock<U>(from + j);
  }
  template <class U>
  [[gnu::always_inline]] decltype(auto) patternBlock(int j, int size) const {
    return run.template patternBlock<U>(from + j, from + size);
  }
};

// Points [0, size) of a run, size ≥ kLanesFrom, drawn by draw(index lanes, pattern lanes,
// lanes used, out) in blocks of U's lanes side by side; a last block of eight or fewer in eight
// lanes when U holds more. Fewer points are drawn one at a time (drawPoint): a block of lanes is
// a long chain of dependent vector multiplies, worth it only for a few points or more.
constexpr int kLanesFrom = 3;
template <class U, class Run, class Draw>
[[gnu::always_inline]] inline void drawRun(const Run& run, int size, Vec2f* out, const Draw& draw) {
  constexpr int kWidth = Lanes<U>::kWidth;
  int j = 0;
  for (; j + kWidth <= size; j += kWidth)
    draw(run.template indexBlock<U>(j), run.template patternBlock<U>(j, size), kWidth, out + j);
  if (j == size) return;
  if constexpr (kWidth > 8)
    if (size - j <= 8) return drawRun<U32x8>(Offset<Run>{run, j}, size - j, out + j, draw);
  // The last block's unused lanes repeat its last point: an index outside the set could start
  // a permutation's cycle walk on a cycle that never enters the domain.
  U index;
  for (int l = 0; l < kWidth; ++l) index[l] = run.index(std::min(j + l, size - 1));
  draw(index, run.template patternBlock<U>(j, size), size - j, out + j);
}

template <class U, class Run>
[[gnu::always_inline]] inline void drawSet(SamplerKind kind, uint32_t n, const Run& run, int size,
                                           Vec2f* out) {
  if (kind == SamplerKind::Sobol)
    return drawRun<U>(
        run, size,
        out, [&](auto i, const auto& p, int lanes, Vec2f* o) __attribute__((always_inline)) {
          sobol2D(p, i, lanes, o);
        });
  const StratifiedSet set(n);
  drawRun<U>(
      run, size,
      out, [&](auto i, const auto& p, int lanes, Vec2f* o) __attribute__((always_inline)) {
        set.draw(i, p, lanes, o);
      });
}

template <class U>
[[gnu::always_inline]] inline void drawSetRunIn(SamplerKind kind, uint32_t n,
                                                const SamplePattern* pattern, uint32_t first,
                                                const SamplePattern* const* patterns,
                                                const uint32_t* flat, int size, Vec2f* out) {
  if (pattern) return drawSet<U>(kind, n, RangeRun(*pattern, first), size, out);
  drawSet<U>(kind, n, ListRun(patterns, flat), size, out);
}

// drawSetRun in blocks of eight, built for baseline x86-64 and for AVX2, chosen by what the CPU
// has: AVX2 holds a block's 64-bit and double lanes in registers, which SSE2 splits and passes
// through memory.
GLINT_AVX2_CLONES(void, drawSetRunIn8,
                  (SamplerKind kind, uint32_t n, const SamplePattern* pattern, uint32_t first,
                   const SamplePattern* const* patterns, const uint32_t* flat, int size,
                   Vec2f* out),
                  (kind, n, pattern, first, patterns, flat, size, out)) {
  drawSetRunIn<U32x8>(kind, n, pattern, first, patterns, flat, size, out);
}
// ... and in blocks of sixteen for AVX-512, which holds them in one register each and multiplies
// 64-bit lanes in one instruction: two blocks' chains of dependent multiplies side by side.
[[gnu::target("avx512f,avx512dq,avx512vl")]] void drawSetRunIn16(
    SamplerKind kind, uint32_t n, const SamplePattern* pattern, uint32_t first,
    const SamplePattern* const* patterns, const uint32_t* flat, int size, Vec2f* out) {
  drawSetRunIn<U32x16>(kind, n, pattern, first, patterns, flat, size, out);
}
const bool kAvx512 = cpuFeatures().avx512FDqVl();
// Whether runs are drawn in sixteen lanes: where the CPU has AVX-512, unless a test chose eight
// (setSamplerLanes). Atomic, as a test may set it while another thread draws (relaxed: a plain
// load on x86).
std::atomic<bool> inSixteenLanes = kAvx512;

// Points of Sobol or stratified sets of n points, at least kLanesFrom, in lanes: [first, first
// + size) of `pattern` where it is given, else flat[j] of *patterns[j].
void drawSetRun(SamplerKind kind, uint32_t n, const SamplePattern* pattern, uint32_t first,
                const SamplePattern* const* patterns, const uint32_t* flat, int size, Vec2f* out) {
  if (inSixteenLanes.load(std::memory_order_relaxed))
    return drawSetRunIn16(kind, n, pattern, first, patterns, flat, size, out);
  drawSetRunIn8(kind, n, pattern, first, patterns, flat, size, out);
}

// The point at flat index `index` of a Sobol or stratified set of n points, alone. Apart from
// drawSetRun: there, each lone point paid for the lanes' stack frame and the keys they hoist.
[[gnu::noinline]] void drawPoint(SamplerKind kind, uint32_t n, const SamplePattern& pattern,
                                 uint32_t index, Vec2f* out) {
  if (kind == SamplerKind::Sobol) return sobol2D(lanesOf(pattern), index, 1, out);
  StratifiedSet(n).draw(index, lanesOf(pattern), 1, out);
}

uint32_t key32(uint64_t h) { return static_cast<uint32_t>(h ^ (h >> 32)); }

// Two independent uniform floats in [0, 1) from one 64-bit hash: 24 bits from each half.
Vec2f unitPair(uint64_t bits) { return {toUnitFloat(bits), toUnitFloat(bits << 32)}; }

}  // namespace

int samplerLanes() { return inSixteenLanes.load(std::memory_order_relaxed) ? 16 : 8; }

bool setSamplerLanes(int width) {
  if (width != 8 && (width != 16 || !kAvx512)) return false;
  inSixteenLanes.store(width == 16, std::memory_order_relaxed);
  return true;
}

std::string_view samplerName(SamplerKind k) {
  switch (k) {
    case SamplerKind::Regular:
      return "regular";
    case SamplerKind::Random:
      return "random";
    case SamplerKind::Stratified:
      return "stratified";
    case SamplerKind::Sobol:
      return "sobol";
  }
  return "?";
}

bool parseSamplerKind(std::string_view name, SamplerKind& out) {
  for (auto k :
       {SamplerKind::Regular, SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol})
    if (samplerName(k) == name) {
      out = k;
      return true;
    }
  return false;
}

uint64_t Sampler::pixelKey(int px, int py) const {
  return hashKey(seed_, static_cast<uint32_t>(px), static_cast<uint32_t>(py));
}

SamplePattern Sampler::pattern(uint64_t pixelKey, uint32_t dim, int half) const {
  // hashKey folds left, so a dimension's pattern hash is hashKey(seed, px, py, dim), and a
  // half's extends it by one more step: the halves' sets are independent of each other.
  constexpr uint64_t kHalfKey = 0x68616c66u;  // "half"
  const uint64_t wholeHash = hashCombine(pixelKey, dim);
  const uint64_t hash = half == kWholeSet
                            ? wholeHash
                            : hashCombine(wholeHash, kHalfKey + static_cast<uint64_t>(half));
  SamplePattern p;
  p.hash = hash;
  p.samples = static_cast<uint32_t>(half == kWholeSet ? spp_ : halfSampleCount(spp_, half));
  if (half != kWholeSet) p.cellStride = 2, p.cellOffset = static_cast<uint32_t>(half);
  p.scramble[0] = key32(hash);
  if (kind_ == SamplerKind::Sobol) {
    p.scramble[1] = key32(mix64(hash + 1));
    p.scramble[2] = key32(mix64(hash + 2));
  }
  p.cellCentres = kind_ == SamplerKind::Regular && dim == dimension(Dim::Pixel);
  return p;
}

Vec2f Sampler::get2D(const SamplePattern& pattern, int index, int sub, int count) const {
  Vec2f out;
  get2D(pattern, index, sub, 1, count, &out);
  return out;
}

void Sampler::get2D(const SamplePattern& pattern, int index, int firstSub, int size, int count,
                    Vec2f* out) const {
  // The shuffle: sample `index` of the pixel takes a permuted stratum of this dimension's set.
  const auto first = static_cast<uint32_t>(index * count + firstSub);
  if (pattern.cellCentres) {
    const int n = static_cast<int>(std::ceil(std::sqrt(double(spp_))));
    for (int j = 0; j < size; ++j) {
      const auto cell = static_cast<int>((first + static_cast<uint32_t>(j)) * pattern.cellStride +
                                         pattern.cellOffset);
      out[j] = {(static_cast<float>(cell % n) + 0.5f) / float(n),
                (static_cast<float>(cell / n) + 0.5f) / float(n)};
    }
    return;
  }
  switch (kind_) {
    case SamplerKind::Random:
      for (int j = 0; j < size; ++j)
        out[j] = unitPair(hashCombine(pattern.hash, first + static_cast<uint32_t>(j)));
      return;
    case SamplerKind::Sobol:
    case SamplerKind::Stratified:
    case SamplerKind::Regular:  // beyond the pixel dimension: stratified
    {
      const uint32_t n = pattern.samples * static_cast<uint32_t>(count);
      if (size >= kLanesFrom)
        return drawSetRun(kind_, n, &pattern, first, nullptr, nullptr, size, out);
      for (int j = 0; j < size; ++j)
        drawPoint(kind_, n, pattern, first + static_cast<uint32_t>(j), out + j);
      return;
    }
  }
}

void Sampler::get2DAt(const SamplePattern* const* patterns, int count, const uint32_t* flat,
                      int size, Vec2f* out) const {
  const auto c = static_cast<uint32_t>(count);
  for (int j = 0; j < size;) {
    // A run of points whose sets are of one size, drawn side by side.
    const uint32_t samples = patterns[j]->samples;
    int end = j + 1;
    if (kind_ == SamplerKind::Sobol || kind_ == SamplerKind::Stratified ||
        (kind_ == SamplerKind::Regular && !patterns[j]->cellCentres))
      while (end < size && patterns[end]->samples == samples && !patterns[end]->cellCentres) ++end;
    if (end - j >= kLanesFrom)
      drawSetRun(kind_, samples * c, nullptr, 0, patterns + j, flat + j, end - j, out + j);
    else
      for (int k = j; k < end; ++k)
        get2D(*patterns[k], static_cast<int>(flat[k] / c), static_cast<int>(flat[k] % c), 1, count,
              out + k);
    j = end;
  }
}

void SubSampleStream::refill() {
  const SamplePattern* patterns[kWindow];
  uint32_t flat[kWindow];
  int m = 0;
  for (; m < kWindow && sample_ < n_; ++m) {
    patterns[m] = &patterns_[sample_];
    flat[m] = static_cast<uint32_t>(indices_[sample_] * count_ + sub_);
    if (++sub_ == count_) sub_ = 0, ++sample_;
  }
  sampler_.get2DAt(patterns, count_, flat, m, window_);
  drawn_ = m;
  used_ = 0;
}

}  // namespace glint
