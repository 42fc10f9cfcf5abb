#include "io/jpeg_texture.h"

// jpeglib.h uses FILE and size_t without including their headers.
#include <cstdio>
#include <cstring>
// clang-format off
#include <jpeglib.h>
#include <jerror.h>
// clang-format on

#include <csetjmp>
#include <memory>
#include <new>
#include <vector>

#include "core/file_names.h"
#include "core/memory.h"
#include "io/texture_reader_support.h"

namespace glint::jpeg_texture {

namespace {

constexpr size_t kMessageSize = 256;
// The start of XMP's APP1 marker (OpenImageIO compares the marker's data with it).
constexpr char kXmpNamespace[] = "http://ns.adobe.com/xap/1.0/";

struct Reader;

// libjpeg's error manager with the reader it reports to: libjpeg hands its callbacks the
// manager, `pub` first.
struct ErrorManager {
  jpeg_error_mgr pub{};
  Reader* reader = nullptr;
};

// An opened JPEG. libjpeg reports errors by calling error_exit, which must not return: it
// longjmps to `jump`, set by the function (marked) that made the libjpeg call. Such functions
// hold no object with a destructor, and everything they fill is allocated before they run.
struct Reader {
  ErrorManager errors;
  jpeg_progress_mgr progress{};
  std::jmp_buf jump{};
  jpeg_decompress_struct jpeg{};
  bool created = false, started = false;
  std::FILE* file = nullptr;
  int width = 0, height = 0, channels = 0;
  int nextRow = 0;
  std::vector<unsigned char> row;
  // libjpeg's error, or its first warning: OpenImageIO reports a warning (a corrupt segment, a
  // premature end) as an error, and its texture is refused.
  bool failed = false;
  char message[kMessageSize] = "";

  Reader() { errors.reader = this; }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  ~Reader() {
    if (created) jpeg_destroy_decompress(&jpeg);
    if (file) std::fclose(file);
  }
};

Reader& readerOf(j_common_ptr jpeg) { return *reinterpret_cast<ErrorManager*>(jpeg->err)->reader; }

void storeMessage(j_common_ptr jpeg) {
  Reader& r = readerOf(jpeg);
  if (r.failed) return;  // the first one says what went wrong
  r.failed = true;
  // libjpeg's allocator failing: the machine's failure, as io/texture_file.cpp recognises it.
  if (jpeg->err->msg_code == JERR_OUT_OF_MEMORY) {
    std::snprintf(r.message, kMessageSize, "%s", std::bad_alloc().what());
    return;
  }
  char text[JMSG_LENGTH_MAX] = "";
  (*jpeg->err->format_message)(jpeg, text);
  std::snprintf(r.message, kMessageSize, "invalid JPEG data: %s", text);
}

[[noreturn]] void exitWithError(j_common_ptr jpeg) {
  storeMessage(jpeg);
  std::longjmp(readerOf(jpeg).jump, 1);
}

// Called for warnings only (error_exit does not call it): kept as the file's failure.
void keepWarning(j_common_ptr jpeg) { storeMessage(jpeg); }

// Called by libjpeg as it reads each scan's data: a file past kMaxScans is refused.
void limitScans(j_common_ptr jpeg) {
  if (!jpeg->is_decompressor) return;
  if (reinterpret_cast<j_decompress_ptr>(jpeg)->input_scan_number <= kMaxScans) return;
  Reader& r = readerOf(jpeg);
  r.failed = true;
  std::snprintf(r.message, kMessageSize, "invalid JPEG data: more than %d scans", kMaxScans);
  std::longjmp(r.jump, 1);
}

// libjpeg calls: the decompressor set up to read from r's file or bytes, keeping the markers
// OpenImageIO keeps (APP0–APP15 and COM), and the header read. False with r->message.
bool readHeader(Reader* r, const unsigned char* bytes, size_t size) {
  if (setjmp(r->jump)) return false;
  jpeg_create_decompress(&r->jpeg);
  r->created = true;
  r->jpeg.progress = &r->progress;
  if (r->file)
    jpeg_stdio_src(&r->jpeg, r->file);
  else
    jpeg_mem_src(&r->jpeg, bytes, static_cast<unsigned long>(size));
  for (int marker = 0; marker < 16; ++marker)
    jpeg_save_markers(&r->jpeg, JPEG_APP0 + marker, 0xffff);
  jpeg_save_markers(&r->jpeg, JPEG_COM, 0xffff);
  if (jpeg_read_header(&r->jpeg, FALSE) != JPEG_HEADER_OK) {
    if (!r->failed) std::snprintf(r->message, kMessageSize, "invalid JPEG data: no image");
    return false;
  }
  // The output's size without starting to decode (jpeg_start_decompress computes it too).
  jpeg_calc_output_dimensions(&r->jpeg);
  return !r->failed;
}

// libjpeg call: decoding started. For a multi-scan file this reads every scan into the
// coefficient buffer. False with r->message.
bool startDecompress(Reader* r) {
  if (setjmp(r->jump)) return false;
  jpeg_start_decompress(&r->jpeg);
  return !r->failed;
}

// libjpeg calls: the next `count` rows, each into r->row and then through `convert`. False with
// r->message.
template <class Convert>
bool readRows(Reader* r, int count, Convert& convert) {
  if (setjmp(r->jump)) return false;
  JSAMPROW row = r->row.data();
  for (int i = 0; i < count; ++i) {
    if (jpeg_read_scanlines(&r->jpeg, &row, 1) != 1 || r->failed) {
      if (!r->failed)
        std::snprintf(r->message, kMessageSize, "invalid JPEG data: a row is missing");
      return false;
    }
    convert(i);
  }
  return true;
}

bool carriesXmp(const jpeg_decompress_struct& jpeg) {
  for (jpeg_saved_marker_ptr m = jpeg.marker_list; m; m = m->next)
    if (m->marker == JPEG_APP0 + 1 && m->data_length >= sizeof kXmpNamespace - 1 &&
        std::memcmp(m->data, kXmpNamespace, sizeof kXmpNamespace - 1) == 0)
      return true;
  return false;
}

// Opens the JPEG `r` reads from (its file, or `bytes`).
void* openReader(std::unique_ptr<Reader> r, const unsigned char* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined) {
  r->jpeg.err = jpeg_std_error(&r->errors.pub);
  r->errors.pub.error_exit = exitWithError;
  r->errors.pub.output_message = keepWarning;
  r->progress.progress_monitor = limitScans;
  if (!readHeader(r.get(), bytes, size)) {
    texture_reader::copyMessage(r->message, error, errorSize);
    return nullptr;
  }
  const J_COLOR_SPACE space = r->jpeg.jpeg_color_space;
  if (space == JCS_CMYK || space == JCS_YCCK || carriesXmp(r->jpeg)) {
    *declined = true;
    return nullptr;
  }
  r->width = int(r->jpeg.output_width);
  r->height = int(r->jpeg.output_height);
  // As OpenImageIO: the file's components (grey 1, colour 3), which libjpeg's output has.
  r->channels = r->jpeg.num_components;
  // OpenImageIO's JPEG reader says sRGB, and its Exif decoder can only say sRGB again.
  texture_reader::fillInfo(info, r->width, r->height, r->channels, false, 1, "sRGB");
  return r.release();
}

bool hasJpegName(const std::string& name) {
  const std::string extension = lowerExtension(name);
  for (const char* jpeg : {".jpg", ".jpeg", ".jpe", ".jif", ".jfif", ".jfi"})
    if (extension == jpeg) return true;
  return false;
}

bool startsAsJpeg(const unsigned char* head, size_t size) {
  return size >= 2 && head[0] == 0xff && head[1] == 0xd8;
}

int readTexels(void* handle, int y0, int y1, int channels, float* out, char* error,
               size_t errorSize) {
  Reader& r = *static_cast<Reader*>(handle);
  if (!texture_reader::rowsInContract(y0, y1, channels, r.height, r.channels, r.nextRow, error,
                                      errorSize))
    return 1;
  if (!r.started) {
    // A multi-scan (progressive) file is decoded into a buffer of its coefficients, two bytes a
    // sample, which the caller's budget did not count.
    if (jpeg_has_multiple_scans(&r.jpeg))
      checkMemoryFits(2.0 * double(r.width) * double(r.height) * double(r.channels),
                      "a multi-scan JPEG texture's coefficients, decoded whole");
    r.row.resize(size_t(r.width) * size_t(r.channels));
    if (!startDecompress(&r)) {
      texture_reader::copyMessage(r.message, error, errorSize);
      return 1;
    }
    r.started = true;
  }
  // OpenImageIO's convert_type: the code times the float reciprocal of 255 (not a division,
  // which rounds some codes differently).
  constexpr float kScale = 1.0f / 255;
  const size_t stride = size_t(r.channels);
  float* to = out;
  const auto convert = [&](int) {
    for (size_t p = 0; p < size_t(r.width); ++p)
      for (int c = 0; c < channels; ++c) *to++ = float(r.row[p * stride + size_t(c)]) * kScale;
  };
  if (!readRows(&r, y1 - y0, convert)) {
    texture_reader::copyMessage(r.message, error, errorSize);
    return 1;
  }
  r.nextRow = y1;
  return 0;
}

void closeReader(void* handle) { delete static_cast<Reader*>(handle); }

}  // namespace

void* open(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
           bool* declined) {
  *declined = false;
  if (!hasJpegName(path)) {
    *declined = true;
    return nullptr;
  }
  auto r = std::make_unique<Reader>();
  r->file = texture_reader::openFile(path, error, errorSize);
  if (!r->file) return nullptr;
  unsigned char head[2] = {};
  if (!startsAsJpeg(head, std::fread(head, 1, sizeof head, r->file))) {
    *declined = true;
    return nullptr;
  }
  std::rewind(r->file);
  return openReader(std::move(r), nullptr, 0, info, error, errorSize, declined);
}

void* openMemory(const std::string& name, const void* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined) {
  const auto* head = static_cast<const unsigned char*>(bytes);
  *declined = !hasJpegName(name) || !startsAsJpeg(head, size);
  if (*declined) return nullptr;
  return openReader(std::make_unique<Reader>(), head, size, info, error, errorSize, declined);
}

const oiio_module::TextureFunctions& functions() {
  static const oiio_module::TextureFunctions f{nullptr, nullptr, readTexels, closeReader};
  return f;
}

}  // namespace glint::jpeg_texture
