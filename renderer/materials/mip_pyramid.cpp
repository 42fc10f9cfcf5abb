#include "materials/mip_pyramid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "core/avx2_clones.h"

namespace glint {

namespace {

using F4 = float __attribute__((vector_size(16)));

// The next level's size along an axis of n texels: half, rounded down, at least one.
int halved(int n) { return std::max(1, n / 2); }

// Which texels of a level of `fine` texels a texel of the next (of `coarse`) averages, and by
// how much: the box of fine texels under it, the ones cut by its edges weighted by the part
// that lies inside (an odd size is not rounded away).
struct Footing {
  int first = 0, count = 0;
  float weight[4] = {0, 0, 0, 0};
};
std::vector<Footing> footings(int fine, int coarse) {
  std::vector<Footing> out(static_cast<size_t>(coarse));
  const double ratio = double(fine) / double(coarse);  // in [2, 3] below the finest level
  for (int i = 0; i < coarse; ++i) {
    const double lo = i * ratio, hi = (i + 1) * ratio;
    Footing& f = out[size_t(i)];
    f.first = int(std::floor(lo));
    for (int x = f.first; x < fine && x < hi && f.count < 4; ++x)
      f.weight[f.count++] = float((std::min(hi, x + 1.0) - std::max(lo, double(x))) / ratio);
  }
  return out;
}

// A coordinate along an axis reduced to one period of its wrap mode, so that the texel index
// computed from it is small (and exact) whatever the coordinate.
[[gnu::always_inline]] inline float reduced(float s, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::Repeat:
      return s - std::floor(s);
    case TextureWrap::MirroredRepeat:
      return s - 2 * std::floor(0.5f * s);
    default:
      return std::clamp(s, -1.0f, 2.0f);
  }
}

// Texel i of an axis of n as the wrap mode continues it; i lies within a texel of the period
// `reduced` left it in.
[[gnu::always_inline]] inline int wrapped(int i, int n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::Repeat:
      return i < 0 ? i + n : i >= n ? i - n : i;
    case TextureWrap::MirroredRepeat:
      if (i < 0) i = -1 - i;
      if (i >= 2 * n) i -= 2 * n;
      return i >= n ? 2 * n - 1 - i : i;
    default:
      return std::clamp(i, 0, n - 1);
  }
}

}  // namespace

MipPyramid::MipPyramid(int width, int height, int channels, std::vector<float> texels)
    : channels_(channels) {
  levels_.push_back({width, height, std::move(texels)});
  levels_.back().texels.push_back(0);
  const size_t c = size_t(channels);
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& fine = levels_.back();
    Level coarse{halved(fine.width), halved(fine.height), {}};
    coarse.texels.assign(size_t(coarse.width) * size_t(coarse.height) * c + 1, 0.0f);
    const std::vector<Footing> xs = footings(fine.width, coarse.width);
    const std::vector<Footing> ys = footings(fine.height, coarse.height);
    for (int y = 0; y < coarse.height; ++y) {
      const Footing& fy = ys[size_t(y)];
      float* out = coarse.texels.data() + size_t(y) * size_t(coarse.width) * c;
      for (int x = 0; x < coarse.width; ++x, out += c) {
        const Footing& fx = xs[size_t(x)];
        for (int j = 0; j < fy.count; ++j) {
          const float* row = fine.texels.data() + size_t(fy.first + j) * size_t(fine.width) * c;
          for (int i = 0; i < fx.count; ++i) {
            const float w = fy.weight[j] * fx.weight[i];
            const float* in = row + size_t(fx.first + i) * c;
            for (size_t k = 0; k < c; ++k) out[k] += w * in[k];
          }
        }
      }
    }
    levels_.push_back(std::move(coarse));
  }
}

double MipPyramid::bytesFor(int width, int height, int channels) {
  // Each level's texels and its padding float, as the constructor makes them.
  const auto levelFloats = [&](int w, int h) { return double(w) * double(h) * channels + 1; };
  double floats = levelFloats(width, height);
  for (int w = width, h = height; w > 1 || h > 1;) {
    w = halved(w);
    h = halved(h);
    floats += levelFloats(w, h);
  }
  return floats * double(sizeof(float));
}

size_t MipPyramid::bytes() const {
  size_t floats = 0;
  for (const Level& level : levels_) floats += level.texels.size();
  return floats * sizeof(float);
}

// The two texels a bilinear lookup reads along an axis of n, from the first one's index i.
// Inside the axis (nearly every lookup) every wrap mode leaves them where they are.
[[gnu::always_inline]] inline void texelPair(int i, int n, TextureWrap wrap, int& a, int& b) {
  if (static_cast<unsigned>(i) < static_cast<unsigned>(n - 1)) {
    a = i;
    b = i + 1;
  } else {
    a = wrapped(i, n, wrap);
    b = wrapped(i + 1, n, wrap);
  }
}

// Inlined into filterChannels: there `sum` is a local array the texels cannot alias, so the
// compiler keeps it in registers instead of checking for overlap and storing at every call.
template <int kCount>
[[gnu::always_inline]] inline void MipPyramid::bilinear(const Level& level, float rs, float rt,
                                                        const ImageFootprint& at, int first,
                                                        float weight, float* sum) const {
  const float x = rs * float(level.width) - 0.5f;
  const float y = rt * float(level.height) - 0.5f;
  const float xFloor = std::floor(x), yFloor = std::floor(y);
  const float fx = x - xFloor, fy = y - yFloor;
  int xa, xb, ya, yb;
  texelPair(int(xFloor), level.width, at.wrapS, xa, xb);
  texelPair(int(yFloor), level.height, at.wrapT, ya, yb);
  const size_t c = size_t(channels_);
  const size_t rowSize = size_t(level.width) * c;
  const float* row0 = level.texels.data() + size_t(ya) * rowSize + size_t(first);
  const float* row1 = level.texels.data() + size_t(yb) * rowSize + size_t(first);
  const size_t ia = size_t(xa) * c, ib = size_t(xb) * c;
  const float w00 = weight * (1 - fx) * (1 - fy), w10 = weight * fx * (1 - fy);
  const float w01 = weight * (1 - fx) * fy, w11 = weight * fx * fy;
  if constexpr (kCount >= 3) {
    // Three or four channels a texel at once, each by the same operations as one alone; a
    // fourth read past the last one falls in the level's padding (Level::texels).
    F4 sum4, t00, t10, t01, t11;
    std::memcpy(&sum4, sum, sizeof sum4);
    std::memcpy(&t00, row0 + ia, sizeof t00);
    std::memcpy(&t10, row0 + ib, sizeof t10);
    std::memcpy(&t01, row1 + ia, sizeof t01);
    std::memcpy(&t11, row1 + ib, sizeof t11);
    sum4 += w00 * t00 + w10 * t10 + w01 * t01 + w11 * t11;
    std::memcpy(sum, &sum4, sizeof sum4);
  } else {
    for (int k = 0; k < kCount; ++k)
      sum[k] += w00 * row0[ia + size_t(k)] + w10 * row0[ib + size_t(k)] +
                w01 * row1[ia + size_t(k)] + w11 * row1[ib + size_t(k)];
  }
}

template <int kCount>
[[gnu::always_inline]] inline void MipPyramid::filterChannels(const ImageFootprint& at, int first,
                                                              float* out) const {
  // Four wide where three or four channels are read (bilinear's vector of them).
  float sum[kCount >= 3 ? 4 : kCount] = {};
  const float s = at.st.x, t = at.st.y;
  if (!std::isfinite(s) || !std::isfinite(t)) {
    for (int k = 0; k < kCount; ++k) out[k] = 0;
    return;
  }
  const float width = float(levels_[0].width), height = float(levels_[0].height);
  // The footprint's axes in finest-level texels and the ellipse they span: its major and minor
  // diameters are the square roots of the eigenvalues of A·Aᵀ + B·Bᵀ (the minor one from the
  // determinant, which does not cancel for a thin ellipse).
  const float ax = at.axisA.x * width, ay = at.axisA.y * height;
  const float bx = at.axisB.x * width, by = at.axisB.y * height;
  const float sxx = ax * ax + bx * bx, sxy = ax * ay + bx * by, syy = ay * ay + by * by;
  const float half = 0.5f * (sxx - syy);
  const float major2 = 0.5f * (sxx + syy) + std::sqrt(half * half + sxy * sxy);
  const float major = std::sqrt(major2);
  // At most a texel (or no footprint: a cut-out's outline, or a NaN one): the finest level.
  if (!(major > 1)) {
    bilinear<kCount>(levels_[0], reduced(s, at.wrapS), reduced(t, at.wrapT), at, first, 1, sum);
    for (int k = 0; k < kCount; ++k) out[k] = sum[k];
    return;
  }
  const int last = int(levels_.size()) - 1;
  if (!(major <= std::numeric_limits<float>::max())) {
    bilinear<kCount>(levels_[size_t(last)], reduced(s, at.wrapS), reduced(t, at.wrapT), at, first,
                     1, sum);
    for (int k = 0; k < kCount; ++k) out[k] = sum[k];
    return;
  }
  const float minor =
      std::max(std::fabs(ax * by - ay * bx) / major, major * (1.0f / kMaxAnisotropy));
  // The level whose texels are as wide as the minor axis (log2 of it): the major axis is
  // covered by points a minor axis apart rather than by blurring along both.
  const float lod = std::log2(std::max(minor, 1.0f));
  int level = std::min(int(lod), last);
  const float upper = level < last ? lod - float(level) : 0;
  const int points =
      std::clamp(int(std::ceil(major / std::max(minor, 1.0f) - 1e-3f)), 1, kMaxAnisotropy);
  // The major axis's direction: an eigenvector of the larger eigenvalue, from the better
  // conditioned of the matrix's two rows.
  float dx = 1, dy = 0;
  if (points > 1) {
    if (sxx >= syy) {
      dx = major2 - syy;
      dy = sxy;
    } else {
      dx = sxy;
      dy = major2 - sxx;
    }
    const float norm = std::sqrt(dx * dx + dy * dy);
    if (norm > 0) {
      dx /= norm;
      dy /= norm;
    } else {
      dx = 1;
      dy = 0;
    }
  }
  // The points at the middles of `points` equal parts of the major diameter, in (s, t).
  const float stepS = dx * major / float(points) / width,
              stepT = dy * major / float(points) / height;
  const float start = -0.5f * float(points - 1);
  const float share = 1.0f / float(points);
  for (int i = 0; i < points; ++i) {
    const float ps = s + (start + float(i)) * stepS, pt = t + (start + float(i)) * stepT;
    // Reduced once for both levels: the same point on each.
    const float rs = reduced(ps, at.wrapS), rt = reduced(pt, at.wrapT);
    bilinear<kCount>(levels_[size_t(level)], rs, rt, at, first, share * (1 - upper), sum);
    if (upper > 0)
      bilinear<kCount>(levels_[size_t(level + 1)], rs, rt, at, first, share * upper, sum);
  }
  for (int k = 0; k < kCount; ++k) out[k] = sum[k];
}

// Built also for AVX2 and chosen by what the CPU has: its floors are one instruction there, not
// a dozen, and the filter's points take most of a textured scene's shading.
GLINT_AVX2_CLONES(void, filterPyramid,
                  (const MipPyramid& pyramid, const ImageFootprint& at, int first, int count,
                   float* out),
                  (pyramid, at, first, count, out)) {
  switch (count) {
    case 1:
      return pyramid.filterChannels<1>(at, first, out);
    case 2:
      return pyramid.filterChannels<2>(at, first, out);
    case 3:
      return pyramid.filterChannels<3>(at, first, out);
    default:
      return pyramid.filterChannels<4>(at, first, out);
  }
}

void MipPyramid::filter(const ImageFootprint& at, int first, int count, float* out) const {
  filterPyramid(*this, at, first, count, out);
}

}  // namespace glint
