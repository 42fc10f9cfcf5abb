#pragma once
// An image held in memory as a MIP pyramid and filtered over a lookup's footprint: how a
// surface reads an image texture (io/texture_file.h reads the file into one). Each level halves
// the one above it by a box filter; a lookup is bilinear at the finest level where the
// footprint is at most a texel, else trilinear between the two levels that bracket the
// footprint's minor axis, at up to 8 points spread along its major axis (an anisotropic
// footprint is not blurred to its longer side). Lookups only read: threads share one pyramid
// with no lock.
#include <cstddef>
#include <vector>

#include "materials/image_texture.h"

namespace glint {

class MipPyramid {
 public:
  // The footprint's major axis over its minor one beyond which the minor axis is widened:
  // the number of points a lookup takes along the major axis is at most this.
  static constexpr int kMaxAnisotropy = 8;

  // `texels`: width × height texels of `channels` floats (1 to 4), row 0 at the top. Each
  // level holds one float more, read and never used by lookups of three channels at once: a
  // vector of `texels` with room for it is not copied.
  MipPyramid(int width, int height, int channels, std::vector<float> texels);

  // The bytes a pyramid of width × height texels of `channels` floats holds: its finest level,
  // at most a third of that again for the smaller ones, and each level's padding float.
  static double bytesFor(int width, int height, int channels);
  // The bytes this pyramid's levels hold, padding included: bytesFor of its size.
  size_t bytes() const;

  int width() const { return levels_[0].width; }
  int height() const { return levels_[0].height; }
  int channels() const { return channels_; }
  int levelCount() const { return int(levels_.size()); }
  // The finest level's texels as given, and the padding float after them.
  const std::vector<float>& texels() const { return levels_[0].texels; }
  // Level `level`'s size and texel (x, y), channel c: what the box filter made of the finest.
  int levelWidth(int level) const { return levels_[size_t(level)].width; }
  int levelHeight(int level) const { return levels_[size_t(level)].height; }
  float texel(int level, int x, int y, int c) const {
    const Level& l = levels_[size_t(level)];
    return l.texels[(size_t(y) * size_t(l.width) + size_t(x)) * size_t(channels_) + size_t(c)];
  }

  // Channels [first, first + count) filtered over the footprint `at` into out[0 .. count).
  // A lookup at a non-finite (s, t) gives 0.
  void filter(const ImageFootprint& at, int first, int count, float* out) const;

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<float> texels;
  };
  friend void filterPyramid(const MipPyramid& pyramid, const ImageFootprint& at, int first,
                            int count, float* out);
  // Its body where Clang with LTO makes its AVX2 copy itself (core/avx2_clones.h).
  friend void filterPyramidIn(const MipPyramid& pyramid, const ImageFootprint& at, int first,
                              int count, float* out);
  template <int kCount>
  inline void filterChannels(const ImageFootprint& at, int first, float* out) const;
  // (rs, rt): the lookup's (s, t) reduced to one period of its wrap modes.
  template <int kCount>
  [[gnu::always_inline]] inline void bilinear(const Level& level, float rs, float rt,
                                              const ImageFootprint& at, int first, float weight,
                                              float* sum) const;

  std::vector<Level> levels_;
  int channels_;
};

}  // namespace glint
