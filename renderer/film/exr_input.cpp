#include "film/exr_input.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTileDescription.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/input_files.h"

namespace glint {

namespace {

// The bytes OpenEXR reads for a value of a fixed-size attribute type; -1 for the others.
int fixedAttributeSize(const std::string& type) {
  static const std::pair<const char*, int> kSizes[] = {{"int", 4},
                                                       {"float", 4},
                                                       {"double", 8},
                                                       {"box2i", 16},
                                                       {"box2f", 16},
                                                       {"v2i", 8},
                                                       {"v2f", 8},
                                                       {"v2d", 16},
                                                       {"v3i", 12},
                                                       {"v3f", 12},
                                                       {"v3d", 24},
                                                       {"m33f", 36},
                                                       {"m33d", 72},
                                                       {"m44f", 64},
                                                       {"m44d", 128},
                                                       {"compression", 1},
                                                       {"lineOrder", 1},
                                                       {"envmap", 1},
                                                       {"deepImageState", 1},
                                                       {"chromaticities", 32},
                                                       {"keycode", 28},
                                                       {"timecode", 8},
                                                       {"rational", 8},
                                                       {"tiledesc", 9}};
  for (const auto& [name, bytes] : kSizes)
    if (type == name) return bytes;
  return -1;
}

}  // namespace

void checkExrHeaders(const std::string& path) {
  checkInputFile(path, kAnyFileSize, "image");
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uint64_t fileSize = std::filesystem::file_size(path, ec);
  if (!in || ec) throw UsageError("cannot read " + path);
  const auto fail = [&](const std::string& why) {
    throw UsageError("cannot read " + path + ": " + why);
  };
  unsigned char start[8] = {};
  if (!in.read(reinterpret_cast<char*>(start), 8) || start[0] != 0x76 || start[1] != 0x2f ||
      start[2] != 0x31 || start[3] != 0x01)
    fail("not an OpenEXR file");
  const bool multipart = (start[5] & 0x10) != 0;  // version flags, byte 1 of the flags
  // OpenEXR reads attribute and type names of at most 31 characters, 255 with the long-names
  // flag, and takes what follows a longer one as the next field: a 90-character name in a file
  // without the flag made it size a string to 640 MB (found by glint_fuzz_exr).
  const size_t attributeNameLimit = (start[5] & 0x04) != 0 ? 255 : 31;
  // A null-terminated name of at most `limit` characters, "" at the end of a header.
  const auto readName = [&](size_t limit) {
    std::string name;
    for (char c; in.get(c);) {
      if (c == '\0') return name;
      if (name.size() == limit)
        fail("a header name is longer than " + std::to_string(limit) + " characters");
      name.push_back(c);
    }
    fail("the header is cut short");
    return name;
  };
  for (int part = 0;; ++part) {
    std::string name = readName(attributeNameLimit);
    if (name.empty()) {
      // The end of the headers: after one for a single-part file, after an empty one (read as
      // an empty first name) for a multi-part file.
      if (!multipart || part > 0) return;
      fail("a multi-part file without parts");
    }
    while (!name.empty()) {
      const std::string type = readName(attributeNameLimit);
      int32_t size = 0;
      if (!in.read(reinterpret_cast<char*>(&size), 4)) fail("the header is cut short");
      const uint64_t at = uint64_t(in.tellg());
      if (size < 0 || uint64_t(size) > fileSize - std::min(at, fileSize))
        fail("its header attribute \"" + excerpt(name) + "\" declares " + std::to_string(size) +
             " bytes, but the file has " + std::to_string(fileSize - std::min(at, fileSize)) +
             " left");
      // OpenEXR reads a value of a fixed-size type by its type, whatever size it declares, and
      // the next attribute from there: a float declaring 255 bytes hid the next attribute's
      // true size from this check (found by glint_fuzz_exr: strings OpenEXR sized to 640 MB).
      if (const int fixed = fixedAttributeSize(type); fixed >= 0 && size != fixed)
        fail("its header attribute \"" + excerpt(name) + "\" of type " + excerpt(type) +
             " declares " + std::to_string(size) + " bytes, not " + std::to_string(fixed));
      if (type == "chlist") {
        // OpenEXR reads a channel list record by record up to its empty name, whatever size
        // it declares, and reads the next attribute from there: so must this check, or a
        // list longer than its size hides the next attribute's true size from it (found by
        // glint_fuzz_exr: a string OpenEXR then sized to 1.8 GB).
        for (std::string channel = readName(255); !channel.empty(); channel = readName(255)) {
          char record[16];  // pixel type, pLinear and 3 reserved bytes, x and y sampling
          if (!in.read(record, sizeof record)) fail("the header is cut short");
          int32_t pixelType = 0, sampling[2] = {};
          std::memcpy(&pixelType, record, 4);
          std::memcpy(sampling, record + 8, 8);
          // OpenEXR takes these as they come: a pixel type beyond UINT, HALF and FLOAT, or a
          // sampling of hundreds of millions, sized its line buffers to 1.8 GB for a 1 kB file
          // (found by glint_fuzz_exr). Real files sample every pixel, or every second one for
          // chroma.
          if (pixelType < 0 || pixelType > 2)
            fail("channel \"" + excerpt(channel) + "\" has pixel type " +
                 std::to_string(pixelType) + " (0 uint, 1 half, 2 float)");
          for (int32_t s : sampling)
            if (s < 1 || s > kMaxChannelSampling)
              fail("channel \"" + excerpt(channel) + "\" is sampled every " + std::to_string(s) +
                   " pixels; 1 to " + std::to_string(kMaxChannelSampling) + " are read");
        }
      } else if (type == "preview") {
        // Likewise a preview image: its width and height, then 4 bytes per pixel, allocated
        // before they are read.
        uint32_t extent[2] = {};
        if (!in.read(reinterpret_cast<char*>(extent), sizeof extent))
          fail("the header is cut short");
        const uint64_t bytes = 4 * uint64_t(extent[0]) * uint64_t(extent[1]);
        const uint64_t left = fileSize - std::min(uint64_t(in.tellg()), fileSize);
        if (bytes > left)
          fail("its preview image declares " + std::to_string(bytes) + " bytes, but the file has " +
               std::to_string(left) + " left");
        in.seekg(std::streamoff(bytes), std::ios::cur);
      } else {
        in.seekg(size, std::ios::cur);
      }
      name = readName(attributeNameLimit);
    }
    if (!multipart) return;
  }
}

namespace {

// Runs `read`, turning OpenEXR's exceptions into a UsageError naming `path` (the file the user
// named is unusable, as a scene with a mistake is); running out of memory is OutOfMemoryError.
template <typename Read>
auto readingFile(const std::string& path, Read&& read) {
  try {
    return read();
  } catch (const UsageError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory while reading " + path);
  } catch (const OutOfMemoryError&) {
    throw;
  } catch (const std::exception& e) {
    throw UsageError("cannot read " + path + ": " + excerpt(e.what()));
  }
}

}  // namespace

namespace {

// The scan lines OpenEXR decodes together, by compression method (its numLinesInBuffer, whose
// header is not installed).
int linesPerBlock(Imf::Compression compression) {
  switch (compression) {
    case Imf::NO_COMPRESSION:
    case Imf::RLE_COMPRESSION:
    case Imf::ZIPS_COMPRESSION:
      return 1;
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION:
      return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION:
      return 32;
    default:  // DWAB; OpenEXR refuses a method it does not know before this is asked
      return 256;
  }
}

// The bytes of one block of a part as OpenEXR sizes its decoding buffers: a scan-line part's
// lines decoded together, across the data window; a tiled part's row of tiles, which it caches
// whole as floats, and by which DWA sizes its scratch. Subsampled channels count in full, as
// DWA counts them. In floating point: a hostile header's channels and width overflow 64 bits.
double exrBlockBytes(const Imf::Header& header) {
  const Imath::Box2i dw = header.dataWindow();
  const double width = double(int64_t{dw.max.x} - dw.min.x + 1);
  double rowBytes = 0;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
    rowBytes += header.hasTileDescription() ? 4 : double(pixelTypeSize(c.channel().type));
  if (!header.hasTileDescription())
    return rowBytes * (width + 1) * linesPerBlock(header.compression());
  const Imf::TileDescription& tiles = header.tileDescription();
  const double tileWidth = std::max(1u, tiles.xSize);
  return rowBytes * std::ceil(width / tileWidth) * tileWidth * tiles.ySize;
}

std::string mebibytes(double bytes) {
  return std::to_string(std::llround(std::min(bytes, 1e18) / (1 << 20))) + " MiB";
}

}  // namespace

std::unique_ptr<Imf::MultiPartInputFile> openExr(const std::string& path) {
  checkExrHeaders(path);
  return readingFile(path, [&] {
    // OpenEXR reads only the headers and chunk tables here; a part's buffers are allocated when
    // it is first read, at the thread count given now, so that is chosen below.
    auto file = std::make_unique<Imf::MultiPartInputFile>(path.c_str(), 0);
    double largestBlock = 0;
    for (int part = 0; part < file->parts(); ++part) {
      const Imf::Header& h = file->header(part);
      if (h.hasType() && Imf::isDeepData(h.type()))
        throw UsageError(path + ": part " + std::to_string(part) +
                         " holds deep data, which Glint does not read");
      // A tiled file is decoded a whole row of tiles at a time, into a cache OpenEXR sizes from
      // the declared tiles: a 10 kB file declaring one tile of 20000 rows would take gigabytes
      // at once. Real files use tiles of 32-256 pixels.
      if (h.hasTileDescription() && (h.tileDescription().xSize > unsigned(kMaxTileEdge) ||
                                     h.tileDescription().ySize > unsigned(kMaxTileEdge)))
        throw UsageError("cannot read " + path + ": its tiles are " +
                         std::to_string(h.tileDescription().xSize) + " x " +
                         std::to_string(h.tileDescription().ySize) + " pixels; at most " +
                         std::to_string(kMaxTileEdge) + " a side are read");
      // OpenEXR sizes a part's line or tile buffers, its row-of-tiles cache and its
      // decompressor's scratch by the block: a few-kB file whose 256-line DWAB blocks were 2 GB
      // wide asked for 2.16 GB at once (found by glint_fuzz_exr).
      const double block = exrBlockBytes(h);
      if (block > double(kMaxExrBlockBytes))
        throw UsageError("cannot read " + path + ": part " + std::to_string(part) +
                         " is decoded in blocks of " + mebibytes(block) +
                         " (its width by the lines decoded together); blocks of at most " +
                         mebibytes(double(kMaxExrBlockBytes)) + " are read");
      largestBlock = std::max(largestBlock, block);
    }
    // OpenEXR keeps two buffers a thread, each a block and its decompressor's scratch: the
    // threads are as many as Glint's EXR threads while those buffers fit the decoding budget.
    const double perThread = 2.0 * kExrScratchPerBlock * std::max(largestBlock, 1.0);
    const int threads = int(std::min(double(std::max(0, Imf::globalThreadCount())),
                                     std::floor(double(kExrDecodingBudget) / perThread)));
    if (threads > 0) {
      file.reset();
      file = std::make_unique<Imf::MultiPartInputFile>(path.c_str(), threads);
    }
    return file;
  });
}

ExrWindow exrWindow(const std::string& path, const Imf::Header& header) {
  const Imath::Box2i dw = header.dataWindow(), disp = header.displayWindow();
  const auto extent = [&](int lo, int hi, const char* what) {
    const int64_t n = int64_t{hi} - lo + 1;
    if (n <= 0 || n > INT32_MAX)
      throw UsageError(path + ": its " + what + " has " + std::to_string(n) + " pixels across");
    return int(n);
  };
  return {dw.min.x,
          dw.min.y,
          extent(dw.min.x, dw.max.x, "data window"),
          extent(dw.min.y, dw.max.y, "data window"),
          extent(disp.min.x, disp.max.x, "display window"),
          extent(disp.min.y, disp.max.y, "display window")};
}

std::vector<std::string> channelsInReadingOrder(const Imf::ChannelList& channels) {
  const auto layerOf = [](const std::string& name) {
    const size_t dot = name.rfind('.');
    return dot == std::string::npos ? std::string() : name.substr(0, dot);
  };
  // Layers in the file's order, the unlayered channels first; in each, R, G, B, A first.
  std::vector<std::string> layers;
  for (auto c = channels.begin(); c != channels.end(); ++c) {
    const std::string layer = layerOf(c.name());
    if (std::find(layers.begin(), layers.end(), layer) == layers.end()) layers.push_back(layer);
  }
  std::stable_partition(layers.begin(), layers.end(),
                        [](const std::string& l) { return l.empty(); });
  std::vector<std::string> ordered;
  for (const std::string& layer : layers) {
    const std::string prefix = layer.empty() ? layer : layer + ".";
    for (const char* component : {"R", "G", "B", "A"})
      if (channels.findChannel(prefix + component)) ordered.push_back(prefix + component);
    for (auto c = channels.begin(); c != channels.end(); ++c)
      if (layerOf(c.name()) == layer &&
          std::find(ordered.begin(), ordered.end(), c.name()) == ordered.end())
        ordered.emplace_back(c.name());
  }
  return ordered;
}

size_t pixelTypeSize(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

void readPixelsInBands(const std::string& path, Imf::MultiPartInputFile& file, int part,
                       const std::vector<ExrSlice>& slices, size_t pixelBytes,
                       const std::function<char*(size_t bytes)>& append) {
  readingFile(path, [&] {
    Imf::InputPart in(file, part);
    const Imf::Header& header = in.header();
    const ExrWindow w = exrWindow(path, header);
    for (const ExrSlice& s : slices) {
      const Imf::Channel* c = header.channels().findChannel(s.name);
      if (c && (c->xSampling != 1 || c->ySampling != 1))
        throw UsageError(path + ": channel " + excerpt(s.name) +
                         " is subsampled, which Glint does not read");
    }
    const size_t rowBytes = size_t(w.width) * pixelBytes;
    // About 16 MB a band, and whole rows of tiles for a tiled file.
    int rows = int(std::clamp<size_t>((size_t(16) << 20) / (rowBytes + 1), 1, 1 << 20));
    if (header.hasTileDescription()) {
      const int tileRows = int(std::max(1u, header.tileDescription().ySize));
      rows = std::max(1, rows / tileRows) * tileRows;
    }
    for (int64_t y = w.y; y < int64_t{w.y} + w.height;) {
      const int64_t end = std::min<int64_t>(y + rows, int64_t{w.y} + w.height);
      char* band = append(rowBytes * size_t(end - y));
      Imf::FrameBuffer frameBuffer;
      for (const ExrSlice& s : slices)
        frameBuffer.insert(
            s.name, Imf::Slice::Make(s.type, band + s.offset, Imath::V2i(w.x, int(y)), w.width,
                                     end - y, pixelBytes, rowBytes));
      in.setFrameBuffer(frameBuffer);
      in.readPixels(int(y), int(end - 1));
      y = end;
    }
  });
}

}  // namespace glint
