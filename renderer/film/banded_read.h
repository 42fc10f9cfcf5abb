#pragma once
// Reads an image's pixels band by band, growing the buffer only as bands decode. A header may
// promise far more pixels than its file holds (a 10 kB EXR declaring 20000 x 20000 RGBA took
// 6.4 GB and four minutes before failing): read this way, it fails at its first missing band,
// having touched only what was read. The full size is reserved first (address space, not
// memory) after film/image_limits.h has checked it fits, so a whole file is never copied.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstddef>
#include <new>
#include <vector>

namespace glint {

// Appends subimage 0 of `in` (spec `spec`), all channels as `type` (TypeUnknown: native), to
// `out`, whose elements are `unitsPerPixel` to a pixel. False on a read error (in.geterror()).
template <typename T>
bool readPixelsInBands(OIIO::ImageInput& in, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                       size_t unitsPerPixel, std::vector<T>& out) {
  const size_t rowUnits = size_t(spec.width) * unitsPerPixel;
  try {
    out.reserve(rowUnits * size_t(spec.height));
  } catch (const std::bad_alloc&) {
    // No address space for it all at once (a small machine's overcommit limit): the bands
    // below grow the buffer as they go.
  }
  // About 16 MB a band, and whole rows of tiles for a tiled file.
  int rows = int(std::clamp<size_t>((size_t(16) << 20) / (rowUnits * sizeof(T) + 1), 1, 1 << 20));
  if (spec.tile_height > 0) rows = std::max(1, rows / spec.tile_height) * spec.tile_height;
  for (int y = spec.y; y < spec.y + spec.height;) {
    const int end = int(std::min<int64_t>(int64_t{y} + rows, int64_t{spec.y} + spec.height));
    const size_t at = out.size();
    out.resize(at + rowUnits * size_t(end - y));
    const bool ok =
        spec.tile_width > 0
            ? in.read_tiles(0, 0, spec.x, spec.x + spec.width, y, end, spec.z, spec.z + 1, 0,
                            spec.nchannels, type, &out[at])
            : in.read_scanlines(0, 0, y, end, spec.z, 0, spec.nchannels, type, &out[at]);
    if (!ok) return false;
    y = end;
  }
  return true;
}

}  // namespace glint
