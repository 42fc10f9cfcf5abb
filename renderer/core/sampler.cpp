// The vector lanes here (and in hash.h's mix64Lanes) never cross a call boundary: everything
// taking them is inlined, so GCC's note that 32-byte vector arguments changed ABI in GCC 4.6
// does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "core/sampler.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/fast_divide.h"
#include "core/hash.h"

namespace glint {

namespace {

// The set [0, len) that a permutation shuffles, with what permute() needs of it precomputed.
struct PermutationDomain {
  PermutationDomain() = default;
  explicit PermutationDomain(uint32_t len) : size(len), mask(len - 1) {
    mask |= mask >> 1;  // the smallest all-ones mask covering len - 1
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
  }
  FastDivisor size;
  uint32_t mask = 0;
};

// One round of permute()'s hash; `w` masks it to the domain's bit width. U is uint32_t, or a
// vector of them (GNU vector extensions, which GCC and Clang share) for lanes side by side.
template <class U>
[[gnu::always_inline]] inline U permuteRound(U i, uint32_t w, uint32_t key) {
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
  return i;
}

// Kensler's hashed permutation ("Correlated Multi-Jittered Sampling", Pixar 2013): a bijection
// on [0, len) chosen by `key`, computed in O(1) without storing a table. Rounds repeat until
// the value falls inside the domain (cycle walking).
uint32_t permute(uint32_t i, const PermutationDomain& domain, uint32_t key) {
  const uint32_t len = domain.size.divisor();
  do i = permuteRound(i, domain.mask, key);
  while (i >= len);
  return domain.size.remainder(i + key);
}

// permute() on [0, 2^b) with w = 2^b − 1: a round never leaves the domain (its last steps mask
// i to w and shift bits down), so there is one round, and the remainder is a mask.
template <class U>
[[gnu::always_inline]] inline U permutePowerOfTwo(U i, uint32_t w, uint32_t key) {
  return (permuteRound(i, w, key) + key) & w;
}

// Two vectors of lanes as one value for permuteRound: each step is applied to both halves in
// turn, so their two chains of dependent multiplies run side by side (a chain's length is its
// multiplies' latency; the core has room for two). Scalars broadcast to both halves.
template <class V>
struct LanePair {
  V a, b;
#define GLINT_LANE_PAIR_OP(op)                                                             \
  friend LanePair operator op(LanePair x, LanePair y) { return {x.a op y.a, x.b op y.b}; } \
  friend LanePair operator op(LanePair x, uint32_t y) { return {x.a op y, x.b op y}; }     \
  LanePair& operator op##=(LanePair y) { return *this = *this op y; }                      \
  LanePair& operator op##=(uint32_t y) { return *this = *this op y; }
  GLINT_LANE_PAIR_OP(^)
  GLINT_LANE_PAIR_OP(*)
  GLINT_LANE_PAIR_OP(&)
  GLINT_LANE_PAIR_OP(+)
  GLINT_LANE_PAIR_OP(>>)
  GLINT_LANE_PAIR_OP(<<)
#undef GLINT_LANE_PAIR_OP
};

// The keys of a set's three permutations (of its n cells, and of a grid's columns and rows),
// from its pattern's scramble.
struct PermutationKeys {
  explicit PermutationKeys(uint32_t p)
      : all(p * 0x51633e2d), column(p * 0xa511e9b3), row(p * 0x63d83595) {}
  uint32_t all, column, row;
};

// The m × k grid of a correlated multi-jittered set of n = m·k samples: m is the largest divisor
// of n not above √n, so every cell holds one sample for any n (a prime n gives a 1×n grid,
// still n-rooks): a grid with m·k > n would leave the same cells empty in every pixel, a bias
// no spp removes.
struct JitterGrid {
  explicit JitterGrid(uint32_t n) {
    auto m = static_cast<uint32_t>(std::max(1.0, std::floor(std::sqrt(double(n)))));
    while (n % m != 0) --m;
    all = PermutationDomain(n);
    columns = PermutationDomain(m);
    rows = PermutationDomain(n / m);
    inverseCount = 1.0 / static_cast<double>(n);
    log2Count = std::has_single_bit(n) ? std::countr_zero(n) : -1;
  }
  PermutationDomain all, columns, rows;
  double inverseCount = 1;
  int log2Count;  // n = 2^log2Count, or -1 when n is not a power of two

  // (stratum + jitter) / n as a float inside [stratum, stratum + 1) / n. The sum is exact in
  // double; rounding the quotient to float can cross the stratum's lower edge when the jitter
  // is within a float ulp of 0, or reach the next stratum's edge when it is within one of 1:
  // such a value steps one ulp back inside (x·n is exact in double for n < 2^29; x ≥ 0 there,
  // so the float one ulp up or down is the bit pattern plus or minus one).
  float place(uint32_t stratum, float jitter) const {
    const auto x = static_cast<float>((static_cast<double>(stratum) + jitter) * inverseCount);
    const double scaled = static_cast<double>(x) * all.size.divisor();
    if (scaled < stratum) [[unlikely]]
      return std::bit_cast<float>(std::bit_cast<uint32_t>(x) + 1);
    if (scaled >= stratum + 1.0) [[unlikely]]
      return std::bit_cast<float>(std::bit_cast<uint32_t>(x) - 1);
    return x;
  }
};

// The grid depends only on n, and a render asks for few distinct n (spp, spp × each light's
// samples): remember the last one per thread instead of rebuilding it per sample.
const JitterGrid& jitterGrid(uint32_t n) {
  thread_local JitterGrid cached(1);
  if (cached.all.size.divisor() != n) cached = JitterGrid(n);
  return cached;
}

// A pixel draws all n samples of each of its sets, so each of the set's m column and k row
// permutations would be recomputed n/m and n/k times. This per-thread table keeps them for the
// sets drawn last. A permutation depends only on its domain and its key, so an entry is found
// by (key, n) and what it returns is what permute() would: the images cannot change.
class AxisPermutationCache {
 public:
  static constexpr uint32_t kMaxSide = 64;  // sets with more columns or rows go uncached

  // permute(column, grid.columns, columnKey) and permute(row, grid.rows, rowKey) of the set
  // with pattern key p, whose grid is `grid`.
  void lookup(const JitterGrid& grid, uint32_t p, uint32_t column, uint32_t row, uint32_t columnKey,
              uint32_t rowKey, uint32_t& sx, uint32_t& sy) {
    const uint32_t n = grid.all.size.divisor();
    if (grid.rows.size.divisor() > kMaxSide) {  // rows ≥ columns
      sx = permute(column, grid.columns, columnKey);
      sy = permute(row, grid.rows, rowKey);
      return;
    }
    Entry& e = entries_[(p ^ (p >> 11) ^ (p >> 23)) % kEntries];
    if (e.key != p || e.n != n) {  // another set's: start afresh
      e.key = p;
      e.n = n;
      e.haveColumn = e.haveRow = 0;
    }
    if (!(e.haveColumn >> column & 1)) {
      e.column[column] = static_cast<uint8_t>(permute(column, grid.columns, columnKey));
      e.haveColumn |= uint64_t{1} << column;
    }
    if (!(e.haveRow >> row & 1)) {
      e.row[row] = static_cast<uint8_t>(permute(row, grid.rows, rowKey));
      e.haveRow |= uint64_t{1} << row;
    }
    sx = e.column[column];
    sy = e.row[row];
  }

 private:
  // A pixel interleaves a set per dimension (pixel, lens, time, and each light and gloss lobe
  // at each depth): room for that many without evicting each other in common scenes.
  static constexpr uint32_t kEntries = 16;
  struct Entry {
    uint32_t key = 0, n = 0;  // n = 0: empty
    uint64_t haveColumn = 0, haveRow = 0;
    uint8_t column[kMaxSide], row[kMaxSide];
  };
  Entry entries_[kEntries];
};

uint32_t key32(uint64_t h) { return static_cast<uint32_t>(h ^ (h >> 32)); }

uint32_t reverseBits(uint32_t x) {
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
uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) {
  x = reverseBits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverseBits(x);
}

// The first two Sobol dimensions form a (0,2)-sequence in base 2: the van der Corput radical
// inverse, and the sequence generated by the Pascal matrix mod 2.
uint32_t sobolDimension0(uint32_t i) { return reverseBits(i); }
uint32_t sobolDimension1(uint32_t i) {
  uint32_t r = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1) r ^= v;
  return r;
}

// Two independent uniform floats in [0, 1) from one 64-bit hash: 24 bits from each half.
Vec2f unitPair(uint64_t bits) { return {toUnitFloat(bits), toUnitFloat(bits << 32)}; }

float bitsToUnit(uint32_t bits) { return static_cast<float>(bits >> 8) * (1.0f / 16777216.0f); }

}  // namespace

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

Vec2f Sampler::stratified2D(const SamplePattern& pattern, int index, int n) {
  Vec2f out;
  stratified2D(pattern, index, 1, n, &out);
  return out;
}

namespace {

// stratified2D for n = 2^b, whose grid sides are powers of two as well: every permutation is
// one round with a mask and every division a shift. Most renders draw such sets (spp and light
// samples are usually powers of two), and the points are stratified2D's bit for bit
// (Sampler.PowerOfTwoSetsMatchTheGeneralConstruction).
struct PowerOfTwoSet {
  PowerOfTwoSet(const JitterGrid& grid, const SamplePattern& pattern)
      : columnBits(static_cast<uint32_t>(std::countr_zero(grid.columns.size.divisor()))),
        rowBits(static_cast<uint32_t>(grid.log2Count) - columnBits),
        all(grid.all.mask),
        columnMask(grid.columns.mask),
        rowMask(grid.rows.mask),
        keys(pattern.scramble[0]),
        hash(pattern.hash),
        offset(hashCombineOffset(hash)),
        scale(std::bit_cast<float>(uint32_t(127 - 24 - grid.log2Count) << 23)) {}

  uint32_t columnBits, rowBits, all, columnMask, rowMask;
  PermutationKeys keys;
  uint64_t hash, offset;  // offset: hashCombineOffset(hash)
  float scale;            // 2^-(24+b)

  // Points [first, first + min(size, N)) at the set indices `index`: N lanes in GNU vector
  // types, which stay in registers (ymm with AVX2, xmm without). U32xN is eight uint32_t
  // lanes, or sixteen as a LanePair of eight. A block is a chain of dependent multiplies
  // (the permutations, then the 64-bit hash), so its time is mostly their latency, and a
  // pair runs two chains side by side.
  template <class U32xN>
  [[gnu::always_inline]] void block(U32xN index, int size, Vec2f* out) const {
    constexpr int N = sizeof(U32xN) / sizeof(uint32_t);
    using U32x4 = uint32_t __attribute__((vector_size(16)));
    using U32x8 = uint32_t __attribute__((vector_size(32)));
    using U64x4 = uint64_t __attribute__((vector_size(32)));
    using I64x4 = int64_t __attribute__((vector_size(32)));
    using I32x4 = int32_t __attribute__((vector_size(16)));
    using F64x4 = double __attribute__((vector_size(32)));
    using F32x4 = float __attribute__((vector_size(16)));
    using F32x8 = float __attribute__((vector_size(32)));
    const U32xN s = permutePowerOfTwo(index, all, keys.all);
    const U32xN row = s >> columnBits, column = s & columnMask;
    const U32xN sx = permutePowerOfTwo(column, columnMask, keys.column);
    const U32xN sy = permutePowerOfTwo(row, rowMask, keys.row);
    // The sample's strata along x and y (as in stratified2D).
    const U32xN strata[2] = {(column << rowBits) + sy, (row << columnBits) + sx};
    // JitterGrid::place for n = 2^b: (stratum + j·2^-24) / n is stratum·2^24 + j (exact in
    // double, below 2^52) times 2^-(24+b), and rounding to float commutes with that scale; so
    // do place()'s edge tests, made here on the rounded value times 2^(24+b).
    // Signed lanes convert to double in one instruction (strata are below 2^28, jitters 2^24).
    // Lanes 4q to 4q + 3.
    const auto quarterOf = [](const U32xN& v, int q) {
      U32x8 half;
      if constexpr (N == 8)
        half = v;
      else
        half = q < 2 ? v.a : v.b;
      return q % 2 == 0 ? __builtin_shufflevector(half, half, 0, 1, 2, 3)
                        : __builtin_shufflevector(half, half, 4, 5, 6, 7);
    };
    const auto place = [&](U32x4 stratum, U64x4 jitter24) {
      const F64x4 low =
          __builtin_convertvector(__builtin_convertvector(stratum, I32x4), F64x4) * 16777216.0;
      const F64x4 jitter = __builtin_convertvector(__builtin_convertvector(jitter24, I32x4), F64x4);
      const F32x4 rounded = __builtin_convertvector(low + jitter, F32x4);
      const F64x4 back = __builtin_convertvector(rounded, F64x4);
      // Comparisons give −1 where true: one ulp up below the stratum, down at its top edge.
      const I64x4 step = (back >= low + 16777216.0) - (back < low);
      return std::bit_cast<F32x4>(std::bit_cast<I32x4>(rounded) +
                                  __builtin_convertvector(step, I32x4)) *
             scale;
    };
    for (int q = 0; q < N / 4 && q * 4 < size; ++q) {
      const U64x4 s64 = __builtin_convertvector(quarterOf(s, q), U64x4);
      const U64x4 bits = mix64Lanes(hash ^ (s64 + offset));  // hashCombine(hash, s) per lane
      // Both jitters from one hash, as unitPair: the top 24 bits, and bits 8–31.
      const F32x4 x = place(quarterOf(strata[0], q), bits >> 40);
      const F32x4 y = place(quarterOf(strata[1], q), (bits & 0xffffffffu) >> 8);
      const F32x8 xy = __builtin_shufflevector(x, y, 0, 4, 1, 5, 2, 6, 3, 7);
      const int n = std::min(4, size - q * 4);
      if (n == 4)
        std::memcpy(static_cast<void*>(out + q * 4), &xy, sizeof xy);
      else
        for (int l = 0; l < n; ++l) out[q * 4 + l] = {xy[2 * l], xy[2 * l + 1]};
    }
  }

  // Points [first, first + size): with kPairs sixteen lanes at a time (and the last eight or
  // fewer in eight), else eight. Pairs pay with AVX2's sixteen ymm registers (8.4 against
  // 10.4 ns per point); the portable build, where eight lanes already take two xmm registers,
  // spills them (25 against 16 ns).
  template <bool kPairs>
  [[gnu::always_inline]] void run(uint32_t first, int size, Vec2f* out) const {
    using U32x8 = uint32_t __attribute__((vector_size(32)));
    const U32x8 lane{0, 1, 2, 3, 4, 5, 6, 7};
    if constexpr (kPairs)
      for (; size > 8; first += 16, out += 16, size -= 16)
        block(LanePair<U32x8>{first + lane, first + 8 + lane}, size, out);
    for (; size > 0; first += 8, out += 8, size -= 8) block(first + lane, size, out);
  }
};

// The same blocks built twice: for baseline x86-64 (pairs of SSE registers) and for AVX2,
// where eight lanes fill one register. Chosen per call by what the CPU has, unless a test
// asks for the portable build (both must give the same bits).
void stratifiedPowerOfTwoPortable(const PowerOfTwoSet& set, uint32_t first, int size, Vec2f* out) {
  set.run<false>(first, size, out);
}
[[gnu::target("avx2")]] void stratifiedPowerOfTwoAvx2(const PowerOfTwoSet& set, uint32_t first,
                                                      int size, Vec2f* out) {
  set.run<true>(first, size, out);
}

// __builtin_cpu_init first: this runs among static constructors, maybe before libgcc's own.
const bool kHaveAvx2 = (__builtin_cpu_init(), __builtin_cpu_supports("avx2"));
std::atomic<bool> forcePortable{false};

void stratifiedPowerOfTwo(const PowerOfTwoSet& set, uint32_t first, int size, Vec2f* out) {
  if (kHaveAvx2 && !forcePortable.load(std::memory_order_relaxed))
    stratifiedPowerOfTwoAvx2(set, first, size, out);
  else
    stratifiedPowerOfTwoPortable(set, first, size, out);
}

}  // namespace

void forcePortableSamplerLanes(bool force) { forcePortable = force; }

void Sampler::stratified2D(const SamplePattern& pattern, int first, int size, int n, Vec2f* out) {
  // A set of one (a 1-spp render's pixel offsets): cell 0, and the point is its jitter, as
  // below with every permutation the identity and place() exact.
  if (n == 1) {
    out[0] = unitPair(hashCombine(pattern.hash, 0));
    return;
  }
  const JitterGrid& grid = jitterGrid(static_cast<uint32_t>(n));
  // One or two points are quicker through the general code: a block of lanes is a long
  // chain of vector multiplies (about 80 ns), worth it from three points on.
  if (grid.log2Count >= 0 && size >= 3)
    return stratifiedPowerOfTwo(PowerOfTwoSet(grid, pattern), static_cast<uint32_t>(first), size,
                                out);
  // Correlated multi-jitter (Kensler 2013): one sample per cell of the m × k grid, placed in its
  // cell so that both 1D projections are stratified too (n-rooks).
  const uint32_t m = grid.columns.size.divisor(), k = grid.rows.size.divisor();
  const uint32_t p = pattern.scramble[0];
  const PermutationKeys keys(p);
  thread_local AxisPermutationCache axes;
  for (int i = 0; i < size; ++i) {
    const uint32_t s = permute(static_cast<uint32_t>(first + i), grid.all, keys.all);
    const uint32_t row = grid.columns.size.quotient(s), column = s - row * m;
    uint32_t sx, sy;
    axes.lookup(grid, p, column, row, keys.column, keys.row, sx, sy);
    // The sample sits in cell (column, row) of the coarse grid and, inside it, in sub-cell
    // (sy, sx) of the fine n × n grid: stratum column·k + sy of n along x, row·m + sx along y.
    // Both jitters come from one hash.
    const Vec2f jitter = unitPair(hashCombine(pattern.hash, s));
    out[i] = {grid.place(column * k + sy, jitter.x), grid.place(row * m + sx, jitter.y)};
  }
}

Vec2f Sampler::sobol2D(const SamplePattern& pattern, int index) {
  // The index is Owen-scrambled too, which shuffles the order of the sequence per pattern while
  // every power-of-two prefix stays a (0,m,2)-net.
  const uint32_t i = nestedUniformScramble(static_cast<uint32_t>(index), pattern.scramble[0]);
  const uint32_t x = nestedUniformScramble(sobolDimension0(i), pattern.scramble[1]);
  const uint32_t y = nestedUniformScramble(sobolDimension1(i), pattern.scramble[2]);
  return {bitsToUnit(x), bitsToUnit(y)};
}

uint64_t Sampler::pixelKey(int px, int py) const {
  return hashKey(seed_, static_cast<uint32_t>(px), static_cast<uint32_t>(py));
}

SamplePattern Sampler::pattern(uint64_t pixelKey, uint32_t dim) const {
  // hashKey folds left, so a dimension's pattern hash is hashKey(seed, px, py, dim).
  const uint64_t hash = hashCombine(pixelKey, dim);
  SamplePattern p;
  p.hash = hash;
  p.scramble[0] = key32(hash);
  if (kind_ == SamplerKind::Sobol) {
    p.scramble[1] = key32(mix64(hash + 1));
    p.scramble[2] = key32(mix64(hash + 2));
  }
  return p;
}

Vec2f Sampler::pixelSampleFor(const SamplePattern& pixel, int index) const {
  if (kind_ == SamplerKind::Regular) {
    const int n = static_cast<int>(std::ceil(std::sqrt(double(spp_))));
    return {(static_cast<float>(index % n) + 0.5f) / float(n),
            (static_cast<float>(index / n) + 0.5f) / float(n)};
  }
  return get2DFor(pixel, index);
}

void Sampler::pixelSamplesFor(const SamplePattern& pixel, int first, int size, Vec2f* out) const {
  if (kind_ == SamplerKind::Regular)
    for (int j = 0; j < size; ++j) out[j] = pixelSampleFor(pixel, first + j);
  else
    get2DRange(pixel, first, size, out);
}

void Sampler::get2DFor(const SamplePattern& pattern, int index, int firstSub, int size, int count,
                       Vec2f* out) const {
  if (kind_ == SamplerKind::Stratified)
    return stratified2D(pattern, index * count + firstSub, size, spp_ * count, out);
  for (int j = 0; j < size; ++j) out[j] = get2DFor(pattern, index, firstSub + j, count);
}

Vec2f Sampler::get2DFor(const SamplePattern& pattern, int index, int sub, int count) const {
  // The shuffle: sample `index` of the pixel takes a permuted stratum of this dimension's set.
  // Regular grids are for pixel offsets only; other dimensions of a regular render stratify.
  const int flat = index * count + sub;
  if (kind_ == SamplerKind::Random)
    return unitPair(hashCombine(pattern.hash, static_cast<uint64_t>(flat)));
  if (kind_ == SamplerKind::Sobol) return sobol2D(pattern, flat);
  return stratified2D(pattern, flat, spp_ * count);
}

}  // namespace glint
