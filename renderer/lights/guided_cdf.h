#pragma once
// Inverting a piecewise-constant distribution's cumulative table, as the environment light draws
// its rows and texels: the cell i with cdf[i] ≤ u < cdf[i + 1], found by a binary search that a
// guide table starts in the right few cells. The guide splits [0, 1) into a power of two of equal
// bins and holds, for each bin's lower edge, where a search for it would end; every u in a bin
// then ends between its edge's answer and the next edge's, so the search of that short stretch
// returns the very cell a search of the whole table would, for every float u.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <type_traits>

namespace glint {

// The guide's bins for a table of n cells: the largest power of two ≤ n, so that it takes no
// more memory than the table and a bin spans about one cell. A power of two makes u·bins and
// j / bins exact, which is what makes the guide's answer exact.
inline int guideBinsFor(int n) {
  int bins = 1;
  while (bins <= n / 2) bins *= 2;
  return bins;
}

// A cumulative table cdf[0..n] (cdf[0] = 0, non-decreasing, ending at exactly 1, or all 0 when
// every weight is 0) and its guide[0..bins] (guideBinsFor(n) + 1 entries), both borrowed.
struct GuidedCdf {
  const float* cdf;
  int n;
  const uint32_t* guide;
  int bins;

  // guide[j] = the index k in [1, n + 1] of the first cdf[k] > j / bins (n + 1: none).
  static void buildGuide(const float* cdf, int n, int bins, uint32_t* guide) {
    for (int j = 0; j <= bins; ++j) {
      const float edge = static_cast<float>(j) / static_cast<float>(bins);
      guide[j] = static_cast<uint32_t>(std::upper_bound(cdf + 1, cdf + n + 1, edge) - cdf);
    }
  }

  // The cell i, in [0, n), with cdf[i] ≤ u < cdf[i + 1]. Cells of zero probability are never
  // chosen: no u lies in them.
  [[gnu::always_inline]] int cell(float u) const {
    const float* above;
    if (u >= 0 && u < 1) [[likely]] {
      const int j = static_cast<int>(u * static_cast<float>(bins));
      above = std::upper_bound(cdf + guide[j], cdf + guide[j + 1], u);
    } else {
      above = std::upper_bound(cdf + 1, cdf + n + 1, u);
    }
    return std::clamp(static_cast<int>(above - cdf) - 1, 0, n - 1);
  }

  // Where u falls, in [0, 1), within the cell from lo = cdf[i] to hi = cdf[i + 1]: for one float
  // or for lanes of them (F, a GNU vector of floats), which round alike.
  template <class F>
  [[gnu::always_inline]] static F within(F u, F lo, F hi) {
    const F width = hi - lo;
    if constexpr (std::is_same_v<F, float>) {
      return width > 0 ? std::clamp((u - lo) / width, 0.0f, 0x1.fffffep-1f) : 0.5f;
    } else {
      // std::clamp's comparisons, lane by lane, chosen by masks (a vector ?: is lane by lane
      // without SSE4.1's blend).
      using I = decltype(u < u);
      const auto bits = [](F x) { return std::bit_cast<I>(x); };
      const F top = F{} + 0x1.fffffep-1f, half = F{} + 0.5f;
      const F q = (u - lo) / width;
      const I aboveTop = top < q;
      const I clamped = ~(q < 0.0f) & ((bits(top) & aboveTop) | (bits(q) & ~aboveTop));
      const I positive = width > 0.0f;
      return std::bit_cast<F>((clamped & positive) | (bits(half) & ~positive));
    }
  }

  // cell() and where u falls within it.
  [[gnu::always_inline]] int find(float u, float& w) const {
    const int i = cell(u);
    w = within(u, cdf[i], cdf[i + 1]);
    return i;
  }
};

}  // namespace glint
