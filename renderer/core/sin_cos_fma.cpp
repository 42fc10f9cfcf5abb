// sinCos's lanes (core/sin_cos.h): only these functions are built for AVX2 and FMA (a flag for
// the whole file would also build its copies of inline library functions so, which the linker
// may then pick for every caller), and every fused multiply-add in them is written out, one for
// each that glibc's FMA build of sincosf performs (sysdeps/ieee754/flt-32/s_sincosf.h, reduce_fast
// and sincosf_poly).
#include <immintrin.h>

#include <cmath>
#include <cstdint>

namespace glint::sin_cos {

namespace {

// Glibc's __sincosf_table[0]: 2/π·2^24, π/2, and the polynomials' coefficients. Its second
// table, taken where the quadrant n has bit 1 set, holds the cosine's negated; the cosine
// polynomial with every coefficient negated rounds to its exact negation (round to nearest is
// symmetric, and the cosine is never zero here), so one table and a sign serve both.
constexpr double kHalfPiInverse = 0x1.45f306dc9c883p+23;
constexpr double kHalfPi = 0x1.921fb54442d18p+0;
constexpr double kC0 = 0x1p+0, kC1 = -0x1.ffffffd0c621cp-2, kC2 = 0x1.55553e1068f19p-5,
                 kC3 = -0x1.6c087e89a359dp-10, kC4 = 0x1.99343027bf8c3p-16;
constexpr double kS1 = -0x1.555545995a603p-3, kS2 = 0x1.1107605230bc4p-7,
                 kS3 = -0x1.994eb3774cf24p-13;

// A float's exponent and top three mantissa bits, as glibc's abstop12 reads them.
inline __m128i abstop(__m128 x) {
  return _mm_and_si128(_mm_srli_epi32(_mm_castps_si128(x), 20), _mm_set1_epi32(0x7ff));
}

// Four lanes from x into s and c; returns a bit per lane left for the C library (|x| ≥ 120,
// infinite or NaN), whose s and c hold anything.
[[gnu::always_inline, gnu::target("avx2,fma")]] inline int fourLanes(const float* x, float* s,
                                                                     float* c) {
  const __m128 xf = _mm_loadu_ps(x);
  const __m256d xd = _mm256_cvtps_pd(xf);
  const __m128i top = abstop(xf);
  // Below 2^-12 glibc answers x and 1; from 120 on it reduces otherwise (not here).
  const __m128i tiny = _mm_cmplt_epi32(top, _mm_set1_epi32(0x398));
  const __m128i large = _mm_cmpgt_epi32(top, _mm_set1_epi32(0x42e));
  // reduce_fast: n = round(x·2/π) by truncating x·2/π·2^24 and rounding in integers, then
  // r = x − n·π/2 in one fused step. Below π/4 n is 0 and r is x, glibc's other branch.
  const __m128i scaled = _mm256_cvttpd_epi32(_mm256_mul_pd(xd, _mm256_set1_pd(kHalfPiInverse)));
  const __m128i n = _mm_srai_epi32(_mm_add_epi32(scaled, _mm_set1_epi32(0x800000)), 24);
  const __m256d r = _mm256_fnmadd_pd(_mm256_cvtepi32_pd(n), _mm256_set1_pd(kHalfPi), xd);
  // sincosf_poly, with its products and fused steps as glibc's build makes them. Glibc
  // multiplies r by the sine's sign, sign[n & 3] = {1, −1, −1, 1}, first; every step of the
  // sine's polynomial is odd, so the sign is put on its float instead (where bits 0 and 1 of n
  // differ), as exact.
  const __m256d x2 = _mm256_mul_pd(r, r);
  const __m256d x3 = _mm256_mul_pd(x2, r);
  const __m256d x4 = _mm256_mul_pd(x2, x2);
  const __m256d x5 = _mm256_mul_pd(x2, x3);
  const __m256d x6 = _mm256_mul_pd(x2, x4);
  const __m256d c1 = _mm256_fmadd_pd(x2, _mm256_set1_pd(kC1), _mm256_set1_pd(kC0));
  const __m256d sinLow = _mm256_fmadd_pd(x3, _mm256_set1_pd(kS1), r);
  const __m256d cosLow = _mm256_fmadd_pd(x4, _mm256_set1_pd(kC2), c1);
  const __m256d sinHigh = _mm256_fmadd_pd(x2, _mm256_set1_pd(kS3), _mm256_set1_pd(kS2));
  const __m256d cosHigh = _mm256_fmadd_pd(x2, _mm256_set1_pd(kC4), _mm256_set1_pd(kC3));
  const __m128i sineNegative = _mm_slli_epi32(_mm_xor_si128(n, _mm_srli_epi32(n, 1)), 31);
  const __m128i cosineNegative = _mm_slli_epi32(_mm_srli_epi32(n, 1), 31);
  const __m128 sinPoly = _mm_xor_ps(_mm256_cvtpd_ps(_mm256_fmadd_pd(sinHigh, x5, sinLow)),
                                    _mm_castsi128_ps(sineNegative));
  const __m128 cosPoly = _mm_xor_ps(_mm256_cvtpd_ps(_mm256_fmadd_pd(cosHigh, x6, cosLow)),
                                    _mm_castsi128_ps(cosineNegative));
  // Odd quadrants swap the two; tiny arguments take x and 1.
  const __m128 odd = _mm_castsi128_ps(_mm_slli_epi32(n, 31));
  const __m128 tinyMask = _mm_castsi128_ps(tiny);
  const __m128 sine = _mm_blendv_ps(_mm_blendv_ps(sinPoly, cosPoly, odd), xf, tinyMask);
  const __m128 cosine =
      _mm_blendv_ps(_mm_blendv_ps(cosPoly, sinPoly, odd), _mm_set1_ps(1.0f), tinyMask);
  _mm_storeu_ps(s, sine);
  _mm_storeu_ps(c, cosine);
  return _mm_movemask_ps(_mm_castsi128_ps(large));
}

}  // namespace

[[gnu::target("avx2,fma")]] void inLanes(const float* x, int n, float* s, float* c) {
  int i = 0;
  for (; i + 4 <= n; i += 4)
    for (int left = fourLanes(x + i, s + i, c + i); left != 0; left &= left - 1) {
      const int k = i + __builtin_ctz(static_cast<unsigned>(left));
      s[k] = ::sinf(x[k]);
      c[k] = ::cosf(x[k]);
    }
  for (; i < n; ++i) {
    s[i] = ::sinf(x[i]);
    c[i] = ::cosf(x[i]);
  }
}

}  // namespace glint::sin_cos
