#include "materials/procedural.h"

#include <cmath>
#include <cstdint>
#include <memory>

#include "core/avx2_clones.h"
#include "core/hash.h"

namespace glint {

namespace {

// ⌊x⌋ as an integer, clamped to ±2^62 (NaN gives −2^62): std::floor is a libm call on baseline
// x86-64, and converting a double beyond the integer range is undefined.
long long floorToInteger(double x) {
  constexpr double kLimit = 0x1p62;
  if (!(std::fabs(x) < kLimit)) return x > 0 ? (1LL << 62) : -(1LL << 62);
  const auto i = static_cast<long long>(x);  // truncates towards zero
  return static_cast<double>(i) > x ? i - 1 : i;
}

// The gradient at a lattice point: one of the 12 edge directions of a cube (Perlin 2002), the
// number g < 12 its hash picks (a hash instead of a permutation table: no period of 256 cells),
// dotted with (x, y, z). Each direction is ±a ± b for two of the three coordinates (a from x or
// y, b from y or z), summed as the expressions `x + y`, `-x - z`, ... would (a negation is
// exact), so the result is the same.
constexpr uint8_t kFirst[12] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1};
constexpr uint8_t kSecond[12] = {1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2};
constexpr double kFirstSign[12] = {1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1};
constexpr double kSecondSign[12] = {1, 1, -1, -1, 1, 1, -1, -1, 1, 1, -1, -1};

// Perlin's quintic fade 6t⁵ − 15t⁴ + 10t³: zero first and second derivatives at 0 and 1.
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double lerp(double t, double a, double b) { return a + t * (b - a); }

}  // namespace

float checkerPattern(const Vec3d& p) {
  // A tiny bias keeps a plane lying exactly on a cell boundary (y = 0) on one side of it.
  constexpr double kBias = 1e-4;
  const auto cell = [](double x) { return floorToInteger(x + kBias); };
  return ((cell(p.x) + cell(p.y) + cell(p.z)) & 1) ? 1.0f : 0.0f;
}

namespace {

// Four doubles, and four lane masks (all ones: true) to choose between two of them.
using D4 = double __attribute__((vector_size(32)));
using M4 = long long __attribute__((vector_size(32)));

// The gradients of a lattice cell's eight corners, hashKey(ix + dx, iy + dy, iz + dz) % 12,
// laid out for perlinNoise's lanes: the corners with dx = 0 in [0], those with dx = 1 in [1],
// lane dy + 2·dz of each holding the choice of the first and second coordinates (firstIsY:
// y, else x; secondIsZ: z, else y) and their signs. Kept as the choice, not the hash, so that
// a cached cell pays no division by 12 per corner and no table look-ups per lane.
struct CellGradients {
  D4 firstSign[2], secondSign[2];
  M4 firstIsY[2], secondIsZ[2];
  long long ix, iy, iz;
  bool filled;
};

// Fills c with the cell's gradients: out of line, so that a remembered cell (nearly every
// lookup) pays only the test.
[[gnu::noinline]] void fillCell(long long ix, long long iy, long long iz, CellGradients& c) {
  // The first two stages shared between the corners that agree on them.
  for (int dx = 0; dx < 2; ++dx) {
    const uint64_t hx = hashKey(uint64_t(ix + dx));
    for (int dy = 0; dy < 2; ++dy) {
      const uint64_t hxy = hashCombine(hx, uint64_t(iy + dy));
      for (int dz = 0; dz < 2; ++dz) {
        const auto g = size_t(hashCombine(hxy, uint64_t(iz + dz)) % 12);
        const int lane = dy + 2 * dz;
        c.firstSign[dx][lane] = kFirstSign[g];
        c.secondSign[dx][lane] = kSecondSign[g];
        c.firstIsY[dx][lane] = kFirst[g] == 1 ? -1 : 0;
        c.secondIsZ[dx][lane] = kSecond[g] == 2 ? -1 : 0;
      }
    }
  }
  c.ix = ix;
  c.iy = iy;
  c.iz = iz;
  c.filled = true;
}

// Hashing is most of the noise's work, and neighbouring shading points mostly fall in the cells
// of their neighbours at every octave but the finest: each thread remembers recent cells' gradients
// (a pure function's results, so the noise is the same whatever the cache holds). 1024 of them
// (288 KiB): a tile's points over all octaves evicted each other from 256. Allocated at a thread's
// first noise, so that no thread of a scene without solid textures carries it.
struct CellCache {
  static constexpr size_t kCells = 1024;
  CellGradients cells[kCells];
};
thread_local std::unique_ptr<CellCache> cellCache;

[[gnu::noinline]] CellCache& newCellCache() {
  cellCache = std::make_unique<CellCache>();  // value-initialised: no cell filled
  return *cellCache;
}

[[gnu::always_inline]] inline const CellGradients& cellGradients(long long ix, long long iy,
                                                                 long long iz) {
  CellCache* cache = cellCache.get();
  CellGradients* cells = cache ? cache->cells : newCellCache().cells;
  const size_t slot = size_t((uint64_t(ix) * 0x9E3779B1u) ^ (uint64_t(iy) * 0x85EBCA77u) ^
                             (uint64_t(iz) * 0xC2B2AE3Du)) %
                      CellCache::kCells;
  CellGradients& c = cells[slot];
  if (!c.filled || c.ix != ix || c.iy != iy || c.iz != iz) [[unlikely]]
    fillCell(ix, iy, iz, c);
  return c;
}

}  // namespace

// The eight corners' gradient products and the four interpolations along x four lanes at once,
// each lane by the scalar formula's operations (the same bits); built also for AVX2, where the
// lanes are one register.
GLINT_AVX2_CLONES(float, perlinNoise, (const Vec3d& p), (p)) {
  const long long ix = floorToInteger(p.x), iy = floorToInteger(p.y), iz = floorToInteger(p.z);
  const double x = p.x - double(ix), y = p.y - double(iy), z = p.z - double(iz);
  const double u = fade(x), v = fade(y), w = fade(z);
  const CellGradients& c = cellGradients(ix, iy, iz);
  // Corner (dx, dy, dz)'s offset from the point, lane dy + 2·dz.
  const D4 ys = {y, y - 1, y, y - 1}, zs = {z, z, z - 1, z - 1};
  D4 dots[2];
  for (int dx = 0; dx < 2; ++dx) {
    const double xd = x - dx;
    const D4 xs = {xd, xd, xd, xd};
    const D4 first = c.firstIsY[dx] ? ys : xs, second = c.secondIsZ[dx] ? zs : ys;
    dots[dx] = c.firstSign[dx] * first + c.secondSign[dx] * second;
  }
  // lerp(u, corner dx = 0, corner dx = 1) in each lane.
  const D4 us = {u, u, u, u};
  const D4 alongX = dots[0] + us * (dots[1] - dots[0]);
  const double n = lerp(w, lerp(v, alongX[0], alongX[1]), lerp(v, alongX[2], alongX[3]));
  // |n| ≤ 1 with these gradients (their dot products with an offset in the unit cell are at
  // most 2, and the fades weight them down to 1 at most); the clamp only guards rounding.
  // As fmax(-1, fmin(1, n)) (NaN gives 1), without their libm calls.
  return float(!(n <= 1.0) ? 1.0 : n < -1.0 ? -1.0 : n);
}

float turbulence(const Vec3d& p, int octaves) {
  double sum = 0, scale = 1;
  for (int i = 0; i < octaves; ++i, scale *= 2) sum += std::fabs(perlinNoise(p * scale)) / scale;
  return float(sum);
}

float noisePattern(const Vec3d& p) { return 0.5f + 0.5f * perlinNoise(p); }

float marblePattern(const Vec3d& p) {
  return float(0.5 + 0.5 * std::sin(p.x + 5.0 * turbulence(p)));
}

float woodPattern(const Vec3d& p) {
  const double rings = std::sqrt(p.x * p.x + p.z * p.z) + 0.5 * turbulence(p * 0.5, 3);
  return float(rings - std::floor(rings));
}

}  // namespace glint
