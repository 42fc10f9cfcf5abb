#include "materials/procedural.h"

#include <cmath>
#include <cstdint>

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
// dotted with (x, y, z). Each direction is ±a ± b for two of the three coordinates: chosen from
// tables, not by a twelve-way branch that the lattice's random hashes mispredict, and summed as
// the expressions `x + y`, `-x - z`, ... would (a negation is exact), so the result is the same.
double gradientDot(unsigned g, double x, double y, double z) {
  static constexpr uint8_t kFirst[12] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1};
  static constexpr uint8_t kSecond[12] = {1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2};
  static constexpr double kFirstSign[12] = {1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1};
  static constexpr double kSecondSign[12] = {1, 1, -1, -1, 1, 1, -1, -1, 1, 1, -1, -1};
  const double p[3] = {x, y, z};
  return kFirstSign[g] * p[kFirst[g]] + kSecondSign[g] * p[kSecond[g]];
}

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

// The gradients of a lattice cell's eight corners, hashKey(ix + dx, iy + dy, iz + dz) % 12 at
// dx + 2·dy + 4·dz: kept as the twelve-way choice, not the hash, so that a cached cell pays no
// division by 12 per corner.
struct CellGradients {
  long long ix, iy, iz;
  bool filled;
  uint8_t corner[8];
};

void cornerGradients(long long ix, long long iy, long long iz, uint8_t* corner) {
  // The first two stages shared between the corners that agree on them.
  for (int dx = 0; dx < 2; ++dx) {
    const uint64_t hx = hashKey(uint64_t(ix + dx));
    for (int dy = 0; dy < 2; ++dy) {
      const uint64_t hxy = hashCombine(hx, uint64_t(iy + dy));
      for (int dz = 0; dz < 2; ++dz)
        corner[dx + 2 * dy + 4 * dz] = uint8_t(hashCombine(hxy, uint64_t(iz + dz)) % 12);
    }
  }
}

// Hashing is most of the noise's work, and neighbouring shading points mostly fall in the cells
// of their neighbours at every octave but the finest: each thread remembers recent cells' gradients
// (a pure function's results, so the noise is the same whatever the cache holds).
const uint8_t* cornerGradients(long long ix, long long iy, long long iz) {
  constexpr size_t kCells = 256;
  thread_local CellGradients cells[kCells];
  const size_t slot = size_t((uint64_t(ix) * 0x9E3779B1u) ^ (uint64_t(iy) * 0x85EBCA77u) ^
                             (uint64_t(iz) * 0xC2B2AE3Du)) %
                      kCells;
  CellGradients& c = cells[slot];
  if (!c.filled || c.ix != ix || c.iy != iy || c.iz != iz) {
    cornerGradients(ix, iy, iz, c.corner);
    c.ix = ix;
    c.iy = iy;
    c.iz = iz;
    c.filled = true;
  }
  return c.corner;
}

}  // namespace

float perlinNoise(const Vec3d& p) {
  const long long ix = floorToInteger(p.x), iy = floorToInteger(p.y), iz = floorToInteger(p.z);
  const double x = p.x - double(ix), y = p.y - double(iy), z = p.z - double(iz);
  const double u = fade(x), v = fade(y), w = fade(z);
  const uint8_t* h = cornerGradients(ix, iy, iz);
  const auto g = [&](int dx, int dy, int dz) {
    return gradientDot(h[dx + 2 * dy + 4 * dz], x - dx, y - dy, z - dz);
  };
  const double n =
      lerp(w, lerp(v, lerp(u, g(0, 0, 0), g(1, 0, 0)), lerp(u, g(0, 1, 0), g(1, 1, 0))),
           lerp(v, lerp(u, g(0, 0, 1), g(1, 0, 1)), lerp(u, g(0, 1, 1), g(1, 1, 1))));
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
