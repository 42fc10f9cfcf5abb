#include "io/png_texture.h"

#include <png.h>

#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string_view>
#include <vector>

#include "core/file_names.h"
#include "core/memory.h"
#include "io/texture_reader_support.h"

namespace glint::png_texture {

namespace {

constexpr size_t kMessageSize = 256;
// The most one of libpng's allocations may take. libpng takes an ancillary chunk's declared
// length on trust when it reads the chunk whole: past its 8 MB limit it only warns (a benign
// error), then allocates and zeroes up to 2 GB before it finds that the file ends (a 458-byte
// file with a text chunk of 1.3 GB took 5.9 s and 1.3 GB). Its legitimate allocations, a row of
// its widest image (1,000,000 texels of 16-bit RGBA: 8 MB) or a decompressed chunk (8 MB), fit
// many times.
constexpr size_t kMaxAllocation = size_t{64} << 20;
constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// An opened PNG. libpng reports errors by longjmp: the functions that call it (marked) hold no
// object with a destructor, and everything they fill is allocated here before they run.
struct Reader {
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::FILE* file = nullptr;
  const unsigned char* bytes = nullptr;  // in memory: the caller's
  size_t size = 0, offset = 0;
  int width = 0, height = 0, channels = 0, bytesPerChannel = 1;
  bool interlaced = false;
  int nextRow = 0;                  // of a file read row by row
  std::vector<unsigned char> rows;  // a band of rows, or an interlaced image whole
  std::vector<unsigned char*> rowPointers;
  bool readWhole = false;        // an interlaced image, read at the first request
  size_t refusedAllocation = 0;  // the size of an allocation past kMaxAllocation, refused
  char message[kMessageSize] = "";

  ~Reader() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    if (file) std::fclose(file);
  }
};

// r->message for an allocation refused by `allocate`.
bool refuseAllocation(Reader* r) {
  std::snprintf(r->message, kMessageSize,
                "invalid PNG data: a chunk that would take %zu bytes (at most %zu MB)",
                r->refusedAllocation, kMaxAllocation >> 20);
  return false;
}

void storeError(png_structp png, png_const_charp message) {
  auto* r = static_cast<Reader*>(png_get_error_ptr(png));
  // libpng's png_malloc failing: the machine's failure, as io/texture_file.cpp recognises it,
  // unless it was a refused allocation.
  const bool outOfMemory = std::string_view(message) == "Out of memory";
  if (r->refusedAllocation)
    refuseAllocation(r);
  else
    std::snprintf(r->message, kMessageSize, "%s%s", outOfMemory ? "" : "invalid PNG data: ",
                  outOfMemory ? std::bad_alloc().what() : message);
  png_longjmp(png, 1);
}

void* allocate(png_structp png, png_alloc_size_t size) {
  if (size > kMaxAllocation) {
    static_cast<Reader*>(png_get_mem_ptr(png))->refusedAllocation = size;
    return nullptr;
  }
  return std::malloc(size);
}

void release(png_structp, png_voidp memory) { std::free(memory); }

// As OpenImageIO's reader: libpng's warnings (and the benign errors it makes warnings of when
// reading) are ignored.
void ignoreWarning(png_structp, png_const_charp) {}

void readBytes(png_structp png, png_bytep out, size_t length) {
  auto* r = static_cast<Reader*>(png_get_io_ptr(png));
  if (r->file) {
    if (std::fread(out, 1, length, r->file) != length)
      png_error(png, std::ferror(r->file) ? "the file could not be read"
                                          : "the file ends before its image data do");
    return;
  }
  if (length > r->size - r->offset) png_error(png, "the bytes end before the image data do");
  std::memcpy(out, r->bytes + r->offset, length);
  r->offset += length;
}

// libpng calls: png_read_info and the transforms OpenImageIO's PNG reader asks for (1-, 2- and
// 4-bit samples to 8, palettes to RGB, tRNS to alpha; 16-bit samples in the machine's order;
// no gamma correction), then the header they give. False with r->message.
bool readHeader(Reader* r) {
  if (setjmp(png_jmpbuf(r->png))) return false;
  png_read_info(r->png, r->info);
  png_set_expand(r->png);
  if constexpr (std::endian::native == std::endian::little) png_set_swap(r->png);
  png_read_update_info(r->png, r->info);
  png_uint_32 width = 0, height = 0;
  int bitDepth = 0, colorType = 0;
  png_get_IHDR(r->png, r->info, &width, &height, &bitDepth, &colorType, nullptr, nullptr, nullptr);
  r->width = int(width);
  r->height = int(height);
  r->channels = png_get_channels(r->png, r->info);
  r->bytesPerChannel = bitDepth == 16 ? 2 : 1;
  r->interlaced = png_get_interlace_type(r->png, r->info) != PNG_INTERLACE_NONE;
  // An allocation refused where libpng only warns (and skips the chunk, or not): refused too.
  return r->refusedAllocation ? refuseAllocation(r) : true;
}

// libpng calls: the next `count` rows into r->rowPointers (a file read row by row, as
// OpenImageIO reads it: png_read_end only for an interlaced file, which is read whole).
bool readRows(Reader* r, int count) {
  if (setjmp(png_jmpbuf(r->png))) return false;
  if (r->interlaced) {
    png_read_image(r->png, r->rowPointers.data());
    png_read_end(r->png, nullptr);
  } else {
    for (int i = 0; i < count; ++i) png_read_row(r->png, r->rowPointers[size_t(i)], nullptr);
  }
  return r->refusedAllocation ? refuseAllocation(r) : true;
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && lowerCase(std::string(a)) == lowerCase(std::string(b));
}

// OpenImageIO 2.4's oiio:ColorSpace for a PNG (png_pvt.h, read_info): "sRGB" for an sRGB chunk
// or none, else from gAMA rounded to hundredths "linear" or "Gamma<g>"; a text chunk whose key
// is oiio:ColorSpace (in any case) then replaces it, the last one winning. The iCCP profile
// sets no colour space; Exif may (the caller declines those files).
std::string declaredColorspace(png_structp png, png_infop info) {
  std::string colorspace = "sRGB";
  int intent = 0;
  double gamma = 0;
  if (!png_get_sRGB(png, info, &intent) && png_get_gAMA(png, info, &gamma) && gamma > 0.0) {
    // OpenImageIO's rounding, float for float.
    float g = float(1.0 / gamma);
    g = roundf(float(100.0 * g)) / 100.0f;
    char text[32];
    std::snprintf(text, sizeof text, "Gamma%.2g", double(g));
    colorspace = g == 1.0f ? "linear" : text;
  }
  png_textp text = nullptr;
  const int count = png_get_text(png, info, &text, nullptr);
  for (int i = 0; i < count; ++i)
    if (equalsIgnoringCase(text[i].key, "oiio:ColorSpace")) colorspace = text[i].text;
  return colorspace;
}

// Whether OpenImageIO would decode Exif from it (an eXIf chunk, or the text chunk ImageMagick
// and exiftool write), which may set its colour space to sRGB, or XMP, whose properties it keeps
// under their own names (oiio:ColorSpace among them).
bool carriesExifOrXmp(png_structp png, png_infop info) {
  png_uint_32 size = 0;
  png_bytep exif = nullptr;
  if (png_get_eXIf_1(png, info, &size, &exif) != 0) return true;
  png_textp text = nullptr;
  const int count = png_get_text(png, info, &text, nullptr);
  for (int i = 0; i < count; ++i)
    if (equalsIgnoringCase(text[i].key, "Raw profile type exif") ||
        equalsIgnoringCase(text[i].key, "XML:com.adobe.xmp"))
      return true;
  return false;
}

// Opens the PNG `r` reads from (its file or bytes, at their start).
void* openReader(std::unique_ptr<Reader> r, GlintOiioTextureInfo* info, char* error,
                 size_t errorSize, bool* declined) {
  r->png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, r.get(), storeError, ignoreWarning,
                                    r.get(), allocate, release);
  if (r->png) r->info = png_create_info_struct(r->png);
  if (!r->png || !r->info) {
    texture_reader::copyMessage(std::bad_alloc().what(), error, errorSize);
    return nullptr;
  }
  png_set_read_fn(r->png, r.get(), readBytes);
  if (!readHeader(r.get())) {
    texture_reader::copyMessage(r->message, error, errorSize);
    return nullptr;
  }
  if (carriesExifOrXmp(r->png, r->info)) {
    *declined = true;
    return nullptr;
  }
  texture_reader::fillInfo(info, r->width, r->height, r->channels, false, r->bytesPerChannel,
                           declaredColorspace(r->png, r->info));
  return r.release();
}

bool hasPngName(const std::string& name) { return lowerExtension(name) == ".png"; }

int readTexels(void* handle, int y0, int y1, int channels, float* out, char* error,
               size_t errorSize) {
  Reader& r = *static_cast<Reader*>(handle);
  if (!texture_reader::rowsInContract(y0, y1, channels, r.height, r.channels,
                                      r.interlaced ? -1 : r.nextRow, error, errorSize))
    return 1;
  const size_t rowBytes = size_t(r.width) * size_t(r.channels) * size_t(r.bytesPerChannel);
  const unsigned char* rows = nullptr;
  if (r.interlaced) {
    // Its passes interleave every row: read whole, as OpenImageIO does. The caller's budget
    // counted a band of rows in the file's type, not the whole image.
    if (!r.readWhole) {
      checkMemoryFits(double(rowBytes) * double(r.height),
                      "an interlaced PNG texture's rows, read whole (its passes interleave them)");
      r.rows.resize(rowBytes * size_t(r.height));
      r.rowPointers.resize(size_t(r.height));
      for (size_t y = 0; y < r.rowPointers.size(); ++y) r.rowPointers[y] = &r.rows[y * rowBytes];
      if (!readRows(&r, r.height)) {
        texture_reader::copyMessage(r.message, error, errorSize);
        return 1;
      }
      r.readWhole = true;
    }
    rows = r.rows.data() + size_t(y0) * rowBytes;
  } else {
    const int count = y1 - y0;
    r.rows.resize(rowBytes * size_t(count));
    r.rowPointers.resize(size_t(count));
    for (size_t y = 0; y < r.rowPointers.size(); ++y) r.rowPointers[y] = &r.rows[y * rowBytes];
    if (!readRows(&r, count)) {
      texture_reader::copyMessage(r.message, error, errorSize);
      return 1;
    }
    r.nextRow = y1;
    rows = r.rows.data();
  }
  // OpenImageIO's convert_type: the code times the float reciprocal of the largest code (not a
  // division, which rounds some codes differently).
  const size_t pixels = size_t(r.width) * size_t(y1 - y0);
  const size_t stride = size_t(r.channels);
  if (r.bytesPerChannel == 1) {
    constexpr float kScale = 1.0f / 255;
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < channels; ++c) *out++ = float(rows[p * stride + size_t(c)]) * kScale;
  } else {
    constexpr float kScale = 1.0f / 65535;
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < channels; ++c) {
        uint16_t code;  // in the machine's order (png_set_swap)
        std::memcpy(&code, rows + 2 * (p * stride + size_t(c)), 2);
        *out++ = float(code) * kScale;
      }
  }
  return 0;
}

void closeReader(void* handle) { delete static_cast<Reader*>(handle); }

}  // namespace

void* open(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
           bool* declined) {
  *declined = false;
  if (!hasPngName(path)) {
    *declined = true;
    return nullptr;
  }
  auto r = std::make_unique<Reader>();
  r->file = texture_reader::openFile(path, error, errorSize);
  if (!r->file) return nullptr;
  unsigned char head[sizeof kSignature] = {};
  const size_t got = std::fread(head, 1, sizeof head, r->file);
  if (got != sizeof head || std::memcmp(head, kSignature, sizeof head) != 0) {
    *declined = true;
    return nullptr;
  }
  std::rewind(r->file);
  return openReader(std::move(r), info, error, errorSize, declined);
}

void* openMemory(const std::string& name, const void* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined) {
  *declined = !hasPngName(name) || size < sizeof kSignature ||
              std::memcmp(bytes, kSignature, sizeof kSignature) != 0;
  if (*declined) return nullptr;
  auto r = std::make_unique<Reader>();
  r->bytes = static_cast<const unsigned char*>(bytes);
  r->size = size;
  return openReader(std::move(r), info, error, errorSize, declined);
}

const oiio_module::TextureFunctions& functions() {
  static const oiio_module::TextureFunctions f{nullptr, nullptr, readTexels, closeReader};
  return f;
}

}  // namespace glint::png_texture
