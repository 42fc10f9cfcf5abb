#include "io/hdr_texture.h"

#include <sys/stat.h>
#include <sys/types.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/file_names.h"
#include "core/memory.h"
#include "io/texture_reader_support.h"
#include "materials/mip_pyramid.h"

namespace glint::hdr_texture {

namespace {

constexpr size_t kMessageSize = 256;
// OpenImageIO reads the header in pieces of this many bytes, each up to its first newline.
constexpr size_t kHeaderPiece = 128;
// OpenImageIO reads at most this many header lines after the first.
constexpr int kMaxHeaderLines = 100;
// Scanlines this wide or wider, or narrower than 8, are never run-length encoded.
constexpr uint64_t kMinEncodedWidth = 8, kMaxEncodedWidth = 0x7fff;

// The file's bytes, or the caller's.
struct Source {
  std::FILE* file = nullptr;
  const unsigned char* bytes = nullptr;
  size_t size = 0, offset = 0;

  size_t read(void* out, size_t n) {
    if (file) return std::fread(out, 1, n, file);
    n = std::min(n, size - offset);
    if (n > 0) std::memcpy(out, bytes + offset, n);
    offset += n;
    return n;
  }
  int64_t tell() const { return file ? int64_t(ftello(file)) : int64_t(offset); }
  // Its whole size in bytes (a file's from fstat; -1 where that fails).
  int64_t total() const {
    if (!file) return int64_t(size);
    struct stat st {};
    return fstat(fileno(file), &st) == 0 ? int64_t(st.st_size) : -1;
  }
  void seek(int64_t position) {
    if (file)
      fseeko(file, off_t(position), SEEK_SET);
    else
      offset = size_t(position);
  }
};

// An opened HDR file, positioned at its next scanline.
struct Reader {
  Source source;
  int width = 0, height = 0;  // the image's, upright
  // Its size line: `scanlines` of `scanlineLength` pixels, along the axes it names. "-Y H +X W"
  // (rows from the top, each from the left) is read a band at a time; the other seven
  // orientations whole, and turned upright.
  int scanlines = 0, scanlineLength = 0;
  bool yFirst = true, yDown = true, xRight = true;
  bool upright() const { return yFirst && yDown && xRight; }
  std::vector<float> whole;  // a file of another orientation, upright, once read
  std::string name;          // the file's path, or an embedded image's name
  int nextRow = 0;
  std::vector<unsigned char> encoded;  // a run-length-encoded scanline's four planes
  std::vector<float> row;              // a scanline's floats, where fewer channels are asked for
  char message[kMessageSize] = "";

  Reader() = default;
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  ~Reader() {
    if (source.file) std::fclose(source.file);
  }

  bool fail(const char* what) {
    std::snprintf(message, kMessageSize, "invalid HDR data: %s", what);
    return false;
  }
  // The file ending before scanline y does.
  bool endsIn(int y) {
    std::snprintf(message, kMessageSize, "invalid HDR data: the pixels end in scanline %d", y);
    return false;
  }
};

// OpenImageIO's exponent table: 2^(e − 136) as written to eight significant digits and read
// back as a float. Most entries are exact powers of two; some are not (2^−96 reads back one ulp
// below it), and the texels are OpenImageIO's only with the same factors.
const std::array<float, 256>& exponents() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int e = 0; e < 256; ++e) {
      char text[32];
      const auto written = std::to_chars(text, text + sizeof text, std::ldexp(1.0, e - 136),
                                         std::chars_format::general, 8);
      std::from_chars(text, written.ptr, t[size_t(e)]);
    }
    return t;
  }();
  return table;
}

void toFloats(const unsigned char rgbe[4], float* out) {
  if (rgbe[3] == 0) {
    out[0] = out[1] = out[2] = 0;
    return;
  }
  const float f = exponents()[rgbe[3]];
  out[0] = float(rgbe[0]) * f;
  out[1] = float(rgbe[1]) * f;
  out[2] = float(rgbe[2]) * f;
}

// OpenImageIO's header line: the next piece of up to kHeaderPiece bytes, cut after its first
// newline unless that is its last byte, the source then placed just after it. Empty at the end.
std::string_view nextLine(Source& source, char (&piece)[kHeaderPiece]) {
  const int64_t at = source.tell();
  const size_t got = source.read(piece, sizeof piece);
  std::string_view line(piece, got);
  if (got == 0) return line;
  const size_t newline = line.find('\n');
  if (newline != std::string_view::npos && newline < got - 1) line = line.substr(0, newline + 1);
  source.seek(at + int64_t(line.size()));
  return line;
}

bool isSpace(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

bool startsAfterSpaces(std::string_view line, std::string_view prefix) {
  while (!line.empty() && isSpace(line.front())) line.remove_prefix(1);
  return line.substr(0, prefix.size()) == prefix;
}

// A run of 1–9 decimal digits at the start of `s`, taken off it.
bool takeNumber(std::string_view& s, int& value) {
  size_t digits = 0;
  while (digits < s.size() && digits < 10 && s[digits] >= '0' && s[digits] <= '9') ++digits;
  if (digits == 0 || digits > 9) return false;
  value = 0;
  for (size_t i = 0; i < digits; ++i) value = value * 10 + (s[i] - '0');
  s.remove_prefix(digits);
  return true;
}

bool take(std::string_view& s, std::string_view prefix) {
  if (s.substr(0, prefix.size()) != prefix) return false;
  s.remove_prefix(prefix.size());
  return true;
}

enum class Header { Read, Refused, Declined };

// OpenImageIO's RGBE_ReadHeader, where it reads the file as Glint does: r->width and height
// from the size line, the source left at the first scanline.
Header readHeader(Reader& r) {
  char piece[kHeaderPiece];
  std::string_view line = nextLine(r.source, piece);
  if (line.empty()) return r.fail("the file ends in its header"), Header::Refused;
  if (line.substr(0, 2) != "#?") return Header::Declined;  // not a Radiance file: OpenImageIO's
  line = nextLine(r.source, piece);
  if (line.empty()) return r.fail("the file ends in its header"), Header::Refused;
  bool format = false;
  for (int lines = 0; lines < kMaxHeaderLines; ++lines) {
    if (line.empty() || line[0] == '\n') break;
    if (line == "FORMAT=32-bit_rle_rgbe\n")
      format = true;
    else if (startsAfterSpaces(line, "GAMMA="))
      return Header::Declined;  // OpenImageIO names a colour space after it
    line = nextLine(r.source, piece);
    if (line.empty()) return r.fail("the file ends in its header"), Header::Refused;
  }
  if (!format) return r.fail("no FORMAT specifier found"), Header::Refused;
  if (line != "\n") return r.fail("missing blank line after FORMAT specifier"), Header::Refused;
  line = nextLine(r.source, piece);
  if (line.empty()) return r.fail("the file ends in its header"), Header::Refused;
  // Radiance's resolution string: "±A n ±B m", the scanlines along axis A (n of them, '-Y' from
  // the top, '+X' from the left), each of m pixels along B. Anything else is OpenImageIO's.
  char firstAxis = 0, secondAxis = 0;
  bool firstUp = false, secondUp = false;
  const auto takeAxis = [&](char& axis, bool& up) {
    if (line.size() < 3 || (line[0] != '-' && line[0] != '+') ||
        (line[1] != 'X' && line[1] != 'Y') || line[2] != ' ')
      return false;
    up = line[0] == '+';
    axis = line[1];
    line.remove_prefix(3);
    return true;
  };
  // A size of 10 digits or more is no image's: refused as the header's, not left to
  // OpenImageIO, which clamped it to 2^31 - 1 and ran out of memory.
  bool tooLong = false;
  const auto size = [&](int& value) {
    if (takeNumber(line, value)) return true;
    tooLong = !line.empty() && line[0] >= '0' && line[0] <= '9';
    return false;
  };
  if (!takeAxis(firstAxis, firstUp) || !size(r.scanlines) || !take(line, " ") ||
      !takeAxis(secondAxis, secondUp) || !size(r.scanlineLength) || line != "\n" ||
      firstAxis == secondAxis) {
    if (tooLong) return r.fail("its size line gives a size of 10 digits or more"), Header::Refused;
    return Header::Declined;
  }
  r.yFirst = firstAxis == 'Y';
  r.yDown = !(r.yFirst ? firstUp : secondUp);
  r.xRight = r.yFirst ? secondUp : firstUp;
  r.height = r.yFirst ? r.scanlines : r.scanlineLength;
  r.width = r.yFirst ? r.scanlineLength : r.scanlines;
  return Header::Read;
}

// OpenImageIO's flat read: `count` pixels of four bytes each.
bool readFlat(Reader& r, float* out, uint64_t count, int y) {
  std::vector<unsigned char>& bytes = r.encoded;
  bytes.resize(size_t(4 * count));
  if (r.source.read(bytes.data(), bytes.size()) != bytes.size()) return r.endsIn(y);
  for (uint64_t i = 0; i < count; ++i) toFloats(&bytes[size_t(4 * i)], out + 3 * i);
  return true;
}

// OpenImageIO's RGBE_ReadPixels_RLE for one scanline: run-length encoded when it starts with
// the marker (2, 2, and its width), else flat from its first pixel.
bool readScanline(Reader& r, float* out, int y) {
  const uint64_t width = uint64_t(r.scanlineLength);
  if (width < kMinEncodedWidth || width > kMaxEncodedWidth) return readFlat(r, out, width, y);
  char what[64];
  unsigned char rgbe[4];
  if (r.source.read(rgbe, 4) != 4) return r.endsIn(y);
  if (rgbe[0] != 2 || rgbe[1] != 2 || (rgbe[2] & 0x80)) {
    toFloats(rgbe, out);
    return readFlat(r, out + 3, width - 1, y);
  }
  if ((uint64_t(rgbe[2]) << 8 | rgbe[3]) != width) {
    std::snprintf(what, sizeof what, "wrong scanline width for scanline %d", y);
    return r.fail(what);
  }
  r.encoded.resize(size_t(4 * width));
  unsigned char* p = r.encoded.data();
  // The four planes (R, G, B, E), each of runs (a count past 128 and one byte) and literals (a
  // count and that many bytes).
  for (int plane = 0; plane < 4; ++plane) {
    const unsigned char* end = r.encoded.data() + size_t(plane + 1) * width;
    while (p < end) {
      unsigned char code[2];
      if (r.source.read(code, 2) != 2) return r.endsIn(y);
      const bool run = code[0] > 128;
      const int count = run ? code[0] - 128 : code[0];
      if (count == 0 || count > end - p) {
        std::snprintf(what, sizeof what, "bad scanline %d data", y);
        return r.fail(what);
      }
      if (run) {
        std::memset(p, code[1], size_t(count));
        p += count;
        continue;
      }
      *p++ = code[1];
      if (count > 1 && r.source.read(p, size_t(count - 1)) != size_t(count - 1)) return r.endsIn(y);
      p += count - 1;
    }
  }
  for (uint64_t i = 0; i < width; ++i) {
    const unsigned char pixel[4] = {r.encoded[size_t(i)], r.encoded[size_t(i + width)],
                                    r.encoded[size_t(i + 2 * width)],
                                    r.encoded[size_t(i + 3 * width)]};
    toFloats(pixel, out + 3 * i);
  }
  return true;
}

void* openReader(std::unique_ptr<Reader> r, GlintOiioTextureInfo* info, char* error,
                 size_t errorSize, bool* declined) {
  switch (readHeader(*r)) {
    case Header::Declined:
      *declined = true;
      return nullptr;
    case Header::Refused:
      texture_reader::copyMessage(r->message, error, errorSize);
      return nullptr;
    case Header::Read:
      break;
  }
  // The fewest bytes its scanlines can take: a scanline is flat (four bytes a pixel) or, where
  // encoded, its marker and each plane's runs of up to 127 bytes, two bytes each. A file with
  // less is refused here, before its texels' memory is allocated for a size it cannot hold.
  const uint64_t width = uint64_t(r->scanlineLength);
  const uint64_t encoded = 4 + 4 * 2 * ((width + 126) / 127);
  const uint64_t leastPerScanline = width < kMinEncodedWidth || width > kMaxEncodedWidth
                                        ? 4 * width
                                        : std::min(4 * width, encoded);
  const int64_t total = r->source.total(), left = total - r->source.tell();
  if (total >= 0 && double(left) < double(leastPerScanline) * double(r->scanlines)) {
    std::snprintf(r->message, kMessageSize,
                  "invalid HDR data: %d x %d pixels cannot fit in the %lld bytes after the header",
                  r->width, r->height, static_cast<long long>(left));
    texture_reader::copyMessage(r->message, error, errorSize);
    return nullptr;
  }
  // OpenImageIO's "presume linear", which only a GAMMA line (declined) changes.
  texture_reader::fillInfo(info, r->width, r->height, 3, true, 4, "linear");
  return r.release();
}

bool hasHdrName(const std::string& name) {
  const std::string extension = lowerExtension(name);
  return extension == ".hdr" || extension == ".rgbe";
}

// A file of another orientation than "-Y +X", read whole into r.whole, upright.
bool readTurned(Reader& r) {
  const size_t width = size_t(r.width), height = size_t(r.height);
  // Beside the MIP pyramid the caller's budget counted (with one band, less than this).
  checkMemoryFits(double(width) * double(height) * 3 * sizeof(float) +
                      MipPyramid::bytesFor(r.width, r.height, 3),
                  "texture " + r.name + " (" + std::to_string(width) + "x" +
                      std::to_string(height) +
                      ", read whole to be turned upright: its scanlines are not rows from the "
                      "top) and its MIP pyramid");
  r.whole.resize(width * height * 3);
  std::vector<float> scanline(3 * size_t(r.scanlineLength));
  for (int s = 0; s < r.scanlines; ++s) {
    if (!readScanline(r, scanline.data(), s)) return false;
    for (int i = 0; i < r.scanlineLength; ++i) {
      const size_t alongY = size_t(r.yFirst ? s : i), alongX = size_t(r.yFirst ? i : s);
      const size_t row = r.yDown ? alongY : height - 1 - alongY;
      const size_t column = r.xRight ? alongX : width - 1 - alongX;
      std::memcpy(&r.whole[3 * (row * width + column)], &scanline[3 * size_t(i)],
                  3 * sizeof(float));
    }
  }
  return true;
}

int readTexels(void* handle, int y0, int y1, int channels, float* out, char* error,
               size_t errorSize) {
  Reader& r = *static_cast<Reader*>(handle);
  if (!texture_reader::rowsInContract(y0, y1, channels, r.height, 3, r.upright() ? r.nextRow : -1,
                                      error, errorSize))
    return 1;
  const size_t width = size_t(r.width);
  if (!r.upright()) {
    if (r.whole.empty() && !readTurned(r)) {
      texture_reader::copyMessage(r.message, error, errorSize);
      return 1;
    }
    for (size_t p = size_t(y0) * width; p < size_t(y1) * width; ++p)
      for (int c = 0; c < channels; ++c) *out++ = r.whole[3 * p + size_t(c)];
    return 0;
  }
  for (int y = y0; y < y1; ++y) {
    float* to = channels == 3 ? out : (r.row.resize(3 * width), r.row.data());
    if (!readScanline(r, to, y)) {
      texture_reader::copyMessage(r.message, error, errorSize);
      return 1;
    }
    if (channels < 3)
      for (size_t p = 0; p < width; ++p)
        for (int c = 0; c < channels; ++c)
          out[p * size_t(channels) + size_t(c)] = to[3 * p + size_t(c)];
    out += width * size_t(channels);
  }
  r.nextRow = y1;
  return 0;
}

void closeReader(void* handle) { delete static_cast<Reader*>(handle); }

}  // namespace

void* open(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
           bool* declined) {
  *declined = !hasHdrName(path);
  if (*declined) return nullptr;
  auto r = std::make_unique<Reader>();
  r->name = path;
  r->source.file = texture_reader::openFile(path, error, errorSize);
  if (!r->source.file) return nullptr;
  return openReader(std::move(r), info, error, errorSize, declined);
}

void* openMemory(const std::string& name, const void* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined) {
  *declined = !hasHdrName(name);
  if (*declined) return nullptr;
  auto r = std::make_unique<Reader>();
  r->name = name;
  r->source.bytes = static_cast<const unsigned char*>(bytes);
  r->source.size = size;
  return openReader(std::move(r), info, error, errorSize, declined);
}

const oiio_module::TextureFunctions& functions() {
  static const oiio_module::TextureFunctions f{nullptr, nullptr, readTexels, closeReader};
  return f;
}

}  // namespace glint::hdr_texture
