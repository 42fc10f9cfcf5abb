#pragma once
// Opening an EXR a user named (glint compare, convert, converge --reference, merge) with
// OpenEXR, only after Glint has checked the file's headers: every attribute's declared size
// must fit in the bytes that follow it. OpenEXR 3.1 allocates a string attribute's declared
// size before reading it, so a 1.7 kB file declaring two 918 MB strings took 1.8 GB (found by
// glint_fuzz_exr).
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPixelType.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace glint {

// The largest tile edge read; openExr refuses files with larger tiles.
inline constexpr int kMaxTileEdge = 4096;
// The coarsest channel sampling a file may declare (chroma channels use 2); openExr refuses
// others. Channels Glint reads must sample every pixel.
inline constexpr int kMaxChannelSampling = 16;

// The largest block (scan lines decoded together, or a row of tiles) read, and the memory
// OpenEXR's decoding buffers may take. It sets up two buffers a thread, each a block and its
// decompressor's scratch (up to 5 blocks with the buffer, DWA's), so openExr opens a file of
// large blocks with fewer threads (none: one buffer).
inline constexpr uint64_t kMaxExrBlockBytes = uint64_t{200} << 20;
inline constexpr uint64_t kExrScratchPerBlock = 5;
inline constexpr uint64_t kExrDecodingBudget = uint64_t{1} << 30;

// Throws UsageError naming `path` when the checks below fail, its blocks exceed
// kMaxExrBlockBytes, or OpenEXR cannot open it.
std::unique_ptr<Imf::MultiPartInputFile> openExr(const std::string& path);

// Throws UsageError naming `path` when it does not start with the OpenEXR magic number, or an
// attribute of one of its headers (every part's, for a multi-part file) declares a negative
// size or more bytes than the file has left.
void checkExrHeaders(const std::string& path);

// A part's data window and display window size, as Glint's images keep them (the display
// window is taken to start at 0, as Glint writes it).
struct ExrWindow {
  int x = 0, y = 0, width = 0, height = 0, fullWidth = 0, fullHeight = 0;
};
// Throws UsageError naming `path` when a window is empty or its size overflows int.
ExrWindow exrWindow(const std::string& path, const Imf::Header& header);

// The part's channels in the order Glint's readers see them: layer by layer, the channels
// without a layer first, then the others in the file's (alphabetical) order; in each layer its
// R, G, B and A first, then its other channels.
std::vector<std::string> channelsInReadingOrder(const Imf::ChannelList& channels);

// One channel of an interleaved pixel buffer: read as `type` at `offset` bytes into a pixel.
struct ExrSlice {
  std::string name;
  Imf::PixelType type;
  size_t offset;
};

// Reads part `part`'s data window in bands of about 16 MB (rows top-down, pixels of
// `pixelBytes` bytes), asking `append(bytes)` for room for each band before decoding it. A
// header may promise far more pixels than its file holds (a 10 kB EXR declaring 20000 x 20000
// RGBA took 6.4 GB and four minutes before failing): read this way, it fails at its first
// missing band, having touched only what was read. Throws UsageError naming `path` on a read
// error.
void readPixelsInBands(const std::string& path, Imf::MultiPartInputFile& file, int part,
                       const std::vector<ExrSlice>& slices, size_t pixelBytes,
                       const std::function<char*(size_t bytes)>& append);

// The same, appended to `out`. The full size is reserved first (address space, not memory),
// after film/image_limits.h has checked that it fits, so the pixels are never copied.
template <typename T>
void readPixelsInBands(const std::string& path, Imf::MultiPartInputFile& file, int part,
                       const std::vector<ExrSlice>& slices, size_t pixelBytes,
                       std::vector<T>& out) {
  const Imath::Box2i dw = file.header(part).dataWindow();
  try {
    out.reserve(size_t(int64_t{dw.max.x} - dw.min.x + 1) *
                size_t(int64_t{dw.max.y} - dw.min.y + 1) * pixelBytes / sizeof(T));
  } catch (const std::bad_alloc&) {
    // No address space for it all at once (a small machine's overcommit limit): the bands
    // grow the buffer as they go.
  }
  readPixelsInBands(path, file, part, slices, pixelBytes, [&](size_t bytes) {
    const size_t at = out.size();
    out.resize(at + bytes / sizeof(T));
    return reinterpret_cast<char*>(out.data() + at);
  });
}

// Bytes of one value of `type` (half 2, float and uint 4).
size_t pixelTypeSize(Imf::PixelType type);

}  // namespace glint
