#include "integrator/point_light_lanes.h"

#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/avx2_clones.h"
#include "core/check.h"
#include "core/ray.h"

// 32-byte vectors never cross a call here, not even to an inlined helper: Clang refuses one
// passed or returned between the AVX2 clone and a function built without AVX.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace glint {

namespace {

constexpr int kWidth = kPointLightLanes;
using F = float __attribute__((vector_size(32)));
using I = int32_t __attribute__((vector_size(32)));
using F4 = float __attribute__((vector_size(16)));
constexpr int32_t kSignBit = std::numeric_limits<int32_t>::min();
constexpr int32_t kMagnitude = std::numeric_limits<int32_t>::max();

// Whether any lane's sign bit is set (a mask's lanes are all ones or zero), four at a time.
[[gnu::always_inline]] inline bool anyOf(const I& mask) {
  const F m = (F)mask;
  return (_mm_movemask_ps(__builtin_shufflevector(m, m, 0, 1, 2, 3)) |
          _mm_movemask_ps(__builtin_shufflevector(m, m, 4, 5, 6, 7))) != 0;
}

// x, y, z of eight Vec3f as three lanes: each vector and the float after it (still inside its
// struct) loaded at once, four at a time transposed. Inserted a float at a time, the loads cost
// more than the arithmetic they fed.
[[gnu::always_inline]] inline void loadLanes(const Vec3f* const (&v)[kWidth], F (&out)[3]) {
  F4 half[2][3];
  for (int h = 0; h < 2; ++h) {
    __m128 r0 = _mm_loadu_ps(&v[4 * h]->x), r1 = _mm_loadu_ps(&v[4 * h + 1]->x),
           r2 = _mm_loadu_ps(&v[4 * h + 2]->x), r3 = _mm_loadu_ps(&v[4 * h + 3]->x);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    half[h][0] = r0;
    half[h][1] = r1;
    half[h][2] = r2;
  }
  for (int c = 0; c < 3; ++c)
    out[c] = __builtin_shufflevector(half[0][c], half[1][c], 0, 1, 2, 3, 4, 5, 6, 7);
}

// offsetAway's last step for each lane, x = p + o rounded one ulp in o's direction
// (nextFloatUp, nextFloatDown): where x is finite its bits' magnitude grows where x and o agree
// in sign and shrinks where they differ; ±0 becomes the smallest subnormal of o's sign; o = ±0
// leaves x. Lanes with ±∞ or NaN (never, in practice) take the scalar rule.
[[gnu::always_inline]] inline void away(const F& x, const F& o, F& out) {
  if (anyOf(~(((F)((I)x & kMagnitude)) < kInfinity))) [[unlikely]] {
    for (int l = 0; l < kWidth; ++l)
      out[l] = o[l] > 0 ? nextFloatUp(x[l]) : o[l] < 0 ? nextFloatDown(x[l]) : x[l];
    return;
  }
  const I xb = (I)x, ob = (I)o;
  const I moves = o != F{};
  const I step = moves & (((xb ^ ob) >> 31) | 1);
  const I fromZero = moves & (x == F{});
  out = (F)((fromZero & ((ob & kSignBit) | 1)) | (~fromZero & (xb + step)));
}

}  // namespace

GLINT_AVX2_CLONES(void, samplePointLight,
                  (const Vec3f& position, const Rgb& intensity, bool inverseSquare,
                   const ShadingPoint* firstPoint, const Vec3f* firstNormal, size_t stride, int n,
                   PointLightLanes& out),
                  (position, intensity, inverseSquare, firstPoint, firstNormal, stride, n, out)) {
  GLINT_CHECK(n <= PointLightLanes::kMaxPoints);
  const auto* pointBytes = reinterpret_cast<const unsigned char*>(firstPoint);
  const auto* normalBytes = reinterpret_cast<const unsigned char*>(firstNormal);
  for (int first = 0; first < n; first += kWidth) {
    // Lanes past n repeat the last point; their results are written and never read.
    const ShadingPoint* s[kWidth];
    const Vec3f* ns[kWidth];
    for (int l = 0; l < kWidth; ++l) {
      const size_t offset = static_cast<size_t>(std::min(first + l, n - 1)) * stride;
      s[l] = reinterpret_cast<const ShadingPoint*>(pointBytes + offset);
      ns[l] = reinterpret_cast<const Vec3f*>(normalBytes + offset);
    }
    F p[3], err[3], ng[3], nv[3];
    loadLanes({&s[0]->p, &s[1]->p, &s[2]->p, &s[3]->p, &s[4]->p, &s[5]->p, &s[6]->p, &s[7]->p}, p);
    loadLanes({&s[0]->pError, &s[1]->pError, &s[2]->pError, &s[3]->pError, &s[4]->pError,
               &s[5]->pError, &s[6]->pError, &s[7]->pError},
              err);
    loadLanes(
        {&s[0]->ng, &s[1]->ng, &s[2]->ng, &s[3]->ng, &s[4]->ng, &s[5]->ng, &s[6]->ng, &s[7]->ng},
        ng);
    loadLanes({ns[0], ns[1], ns[2], ns[3], ns[4], ns[5], ns[6], ns[7]}, nv);
    // lightSampleFrom: one square root and one division serve the direction and the inverse
    // square.
    const F tx = position.x - p[0], ty = position.y - p[1], tz = position.z - p[2];
    const F dist2 = tx * tx + ty * ty + tz * tz;
    const F4 distLo = _mm_sqrt_ps(__builtin_shufflevector(dist2, dist2, 0, 1, 2, 3));
    const F4 distHi = _mm_sqrt_ps(__builtin_shufflevector(dist2, dist2, 4, 5, 6, 7));
    const F invDist = 1.0f / __builtin_shufflevector(distLo, distHi, 0, 1, 2, 3, 4, 5, 6, 7);
    const F wx = tx * invDist, wy = ty * invDist, wz = tz * invDist;
    const F cosine = nv[0] * wx + nv[1] * wy + nv[2] * wz;
    const F invDist2 = invDist * invDist;
    const F ir = inverseSquare ? intensity.r * invDist2 : F{} + intensity.r;
    const F ig = inverseSquare ? intensity.g * invDist2 : F{} + intensity.g;
    const F ib = inverseSquare ? intensity.b * invDist2 : F{} + intensity.b;
    const I contributes = (cosine > F{}) & ~((ir == F{}) & (ig == F{}) & (ib == F{}));
    std::memcpy(out.wi[0] + first, &wx, sizeof wx);
    std::memcpy(out.wi[1] + first, &wy, sizeof wy);
    std::memcpy(out.wi[2] + first, &wz, sizeof wz);
    std::memcpy(out.intensity[0] + first, &ir, sizeof ir);
    std::memcpy(out.intensity[1] + first, &ig, sizeof ig);
    std::memcpy(out.intensity[2] + first, &ib, sizeof ib);
    std::memcpy(out.contributes + first, &contributes, sizeof contributes);
    // spawnShadowRayInto: from p, or on a smooth mesh from p lifted towards the smooth surface,
    // whose sum carries one more rounding; then offsetRayOrigin towards the light.
    F from[3] = {p[0], p[1], p[2]}, e[3] = {err[0], err[1], err[2]};
    bool anyLifted = false;
    for (int l = 0; l < kWidth; ++l) anyLifted |= s[l]->lifted;
    if (anyLifted) [[unlikely]] {
      I lifted;
      for (int l = 0; l < kWidth; ++l) lifted[l] = s[l]->lifted ? -1 : 0;
      F lift[3];
      loadLanes({&s[0]->shadowLift, &s[1]->shadowLift, &s[2]->shadowLift, &s[3]->shadowLift,
                 &s[4]->shadowLift, &s[5]->shadowLift, &s[6]->shadowLift, &s[7]->shadowLift},
                lift);
      for (int c = 0; c < 3; ++c) {
        const F liftedFrom = p[c] + lift[c];
        from[c] = lifted ? liftedFrom : p[c];
        e[c] = lifted ? err[c] + gamma(2) * (F)((I)liftedFrom & kMagnitude) : err[c];
      }
    }
    const F along = (F)((I)ng[0] & kMagnitude) * e[0] + (F)((I)ng[1] & kMagnitude) * e[1] +
                    (F)((I)ng[2] & kMagnitude) * e[2];
    const F w[3] = {position.x - from[0], position.y - from[1], position.z - from[2]};
    // Negated (its sign bit flipped) where the light is behind the geometric normal.
    const I flip = ((w[0] * ng[0] + w[1] * ng[1] + w[2] * ng[2]) < F{}) & kSignBit;
    for (int c = 0; c < 3; ++c) {
      const F offset = (F)((I)(along * ng[c]) ^ flip);
      F o;
      away(from[c] + offset, offset, o);
      const F d = position[c] - o;
      std::memcpy(out.o[c] + first, &o, sizeof o);
      std::memcpy(out.d[c] + first, &d, sizeof d);
    }
  }
}

}  // namespace glint
