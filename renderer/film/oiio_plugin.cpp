// libglint_oiio.so: the only code linked against OpenImageIO (film/oiio_module.h).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "film/oiio_module_abi.h"

extern "C" __attribute__((visibility("default"))) int glint_oiio_write_image(
    const char* formatPath, const char* path, int width, int height, int channels, int bits,
    const void* pixels, char* error, size_t errorSize) {
  // No exception may cross this C boundary.
  try {
    const OIIO::TypeDesc type = bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(width, height, channels, type);
    // Glint's 4-channel display images hold straight alpha (film/display.h): a TIFF marks it
    // unassociated (ExtraSamples 2) rather than premultiplied.
    if (channels == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(formatPath);
    if (out && out->open(path, spec) && out->write_image(type, pixels) && out->close()) return 0;
    std::snprintf(error, errorSize, "%s", (out ? out->geterror() : OIIO::geterror()).c_str());
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return 1;
}
static_assert(std::is_same_v<decltype(&glint_oiio_write_image), GlintOiioWriteImage>);

namespace {

// An image opened for reading as a texture: its reader, and for an image held in memory the
// proxy the reader reads the caller's bytes through.
struct OpenedImage {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
  std::unique_ptr<OIIO::ImageInput> in;
};

// Why a texture's first channels, which Glint reads as its colour (or data) and alpha, are not
// those of a texture; empty where they are. Names mean something only where the file can
// name them freely (OpenEXR): there three or more channels must begin with R, G, B (A) or
// X, Y, Z (Red, Green, Blue; any case), under one layer's prefix or none. A frame's depth or a
// chroma image (Y, RY, BY) was read as colour.
std::string unreadChannels(const OIIO::ImageInput& in) {
  const OIIO::ImageSpec& spec = in.spec();
  if (std::string_view(in.format_name()) != "openexr" || spec.nchannels < 3 ||
      spec.channelnames.size() < 3)
    return "";
  const auto suffix = [&](int c, std::string& prefix) {
    const std::string& name = spec.channelnames[size_t(c)];
    const size_t dot = name.rfind('.');
    prefix = dot == std::string::npos ? "" : name.substr(0, dot + 1);
    return dot == std::string::npos ? name : name.substr(dot + 1);
  };
  std::string prefix[3], names[3];
  for (int c = 0; c < 3; ++c) names[c] = suffix(c, prefix[c]);
  const bool oneLayer = prefix[0] == prefix[1] && prefix[1] == prefix[2];
  // Upper case, as OpenImageIO matches colour channel names.
  for (std::string& n : names)
    for (char& ch : n) ch = char(std::toupper(static_cast<unsigned char>(ch)));
  const auto are = [&](const char* a, const char* b, const char* c) {
    return names[0] == a && names[1] == b && names[2] == c;
  };
  if (oneLayer && (are("R", "G", "B") || are("RED", "GREEN", "BLUE") || are("X", "Y", "Z")))
    return "";
  std::string list;
  for (size_t c = 0; c < spec.channelnames.size() && c < 8; ++c)
    list += (c ? ", " : "") + spec.channelnames[c];
  if (spec.channelnames.size() > 8) list += ", ...";
  return "its channels are " + list +
         "; Glint reads a texture's first three channels as R, G, B (or X, Y, Z), and these are "
         "not (oiiotool --ch R=...,G=...,B=... names the ones to read)";
}

// Opens `name` (through `proxy` when it is held in memory) with the reader of `format` alone
// and fills `info` from its header; null with OpenImageIO's message. ImageInput::open would try
// every other reader on a file its extension's reader refused (io/texture_formats.h says why
// a texture must not reach them).
void* openImage(const char* name, const char* format,
                std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy, GlintOiioTextureInfo* info,
                char* error, size_t errorSize) {
  auto image = std::make_unique<OpenedImage>();
  image->proxy = std::move(proxy);
  OIIO::ImageSpec config;
  // Colours stay as the file stores them, not premultiplied by alpha (a cut-out's edge keeps
  // its colour).
  config.attribute("oiio:UnassociatedAlpha", 1);
  if (image->proxy) {
    OIIO::Filesystem::IOProxy* p = image->proxy.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
  }
  // A bare format name: the reader is made, not tried on the file.
  image->in = OIIO::ImageInput::create(format);
  if (!image->in) {
    std::snprintf(error, errorSize, "%s", OIIO::geterror().c_str());
    return nullptr;
  }
  // A reader without proxies would open a file of the embedded image's name instead.
  if (image->proxy && !image->in->supports("ioproxy")) {
    std::snprintf(error, errorSize, "OpenImageIO's %s reader does not read images held in memory",
                  format);
    return nullptr;
  }
  OIIO::ImageSpec opened;
  if (!image->in->open(name, opened, config)) {
    std::string why = image->in->geterror();
    std::snprintf(error, errorSize, "%s",
                  why.empty() ? "OpenImageIO could not open it" : why.c_str());
    return nullptr;
  }
  const OIIO::ImageSpec& spec = image->in->spec();
  info->width = spec.width;
  info->height = spec.height;
  info->channels = spec.nchannels;
  info->isFloat = spec.format.is_floating_point();
  info->bytesPerChannel = int(spec.format.size());
  std::snprintf(info->colorspace, sizeof info->colorspace, "%s",
                spec.get_string_attribute("oiio:ColorSpace").c_str());
  info->tileHeight = spec.tile_width > 0 ? std::max(spec.tile_height, 1) : 0;
  if (spec.deep) {
    std::snprintf(error, errorSize, "it holds deep data, which Glint does not read");
    return nullptr;
  }
  if (const std::string why = unreadChannels(*image->in); !why.empty()) {
    std::snprintf(error, errorSize, "%s", why.c_str());
    return nullptr;
  }
  if (spec.tile_width > 0 && spec.tile_depth > 1) {
    std::snprintf(error, errorSize, "a volume texture (tiles %d deep) is not supported",
                  spec.tile_depth);
    return nullptr;
  }
  return image.release();
}

// Rows [y0, y1) of a scanline image's first `channels` channels, as floats. Asked for any type
// but UNKNOWN ("the file's own", which FLOAT from a float file is not), OpenImageIO 2.4's
// read_scanlines converts through a buffer of 64 MB at every call, whatever the band's size;
// asked for UNKNOWN it reads into the caller's buffer (through one of the band's size holding
// every channel, where only the first are kept), which io/texture_file.cpp's memory check
// counts. convert_pixel_values is what read_scanlines converts with: the same floats.
bool readScanlines(OIIO::ImageInput& in, int y0, int y1, int channels, float* out) {
  const OIIO::ImageSpec& spec = in.spec();
  const auto read = [&](OIIO::TypeDesc type, void* to) {
    return in.read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, channels, type, to);
  };
  const size_t values = size_t(spec.width) * size_t(y1 - y0) * size_t(channels);
  // A type per channel, which OpenImageIO converts channel by channel, or a band past the int
  // that convert_pixel_values counts in (a single row of 2^29 pixels): OpenImageIO's own
  // conversion, through its 64 MB buffer.
  if (!spec.channelformats.empty() || values > size_t(INT_MAX))
    return read(OIIO::TypeDesc::FLOAT, out);
  if (spec.format == OIIO::TypeDesc::FLOAT) return read(OIIO::TypeDesc::UNKNOWN, out);
  std::vector<unsigned char> band(values * spec.format.size());
  return read(OIIO::TypeDesc::UNKNOWN, band.data()) &&
         OIIO::convert_pixel_values(spec.format, band.data(), OIIO::TypeDesc::FLOAT, out,
                                    int(values));
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void* glint_oiio_texture_open(
    const char* path, const char* format, GlintOiioTextureInfo* info, char* error,
    size_t errorSize) {
  try {
    return openImage(path, format, nullptr, info, error, errorSize);
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return nullptr;
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_open), GlintOiioTextureOpen>);

extern "C" __attribute__((visibility("default"))) void* glint_oiio_texture_open_memory(
    const char* name, const char* format, const void* bytes, size_t size,
    GlintOiioTextureInfo* info, char* error, size_t errorSize) {
  try {
    return openImage(name, format, std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size),
                     info, error, errorSize);
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return nullptr;
}
static_assert(
    std::is_same_v<decltype(&glint_oiio_texture_open_memory), GlintOiioTextureOpenMemory>);

extern "C" __attribute__((visibility("default"))) int glint_oiio_texture_read(
    void* handle, int y0, int y1, int channels, float* out, char* error, size_t errorSize) {
  try {
    OIIO::ImageInput& in = *static_cast<OpenedImage*>(handle)->in;
    const OIIO::ImageSpec& spec = in.spec();
    // OpenImageIO's TIFF reader reports a truncated file's missing strips as errors yet says it
    // succeeded: any error it reports refuses the file.
    // OpenImageIO 2.4's read_scanlines divides by zero on a tiled file: tiles are read as tiles.
    const bool read =
        spec.tile_width > 0
            ? in.read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y0, spec.y + y1, spec.z,
                            spec.z + 1, 0, channels, OIIO::TypeDesc::FLOAT, out)
            : readScanlines(in, y0, y1, channels, out);
    if (read && !in.has_error()) return 0;
    std::string why = in.geterror();
    why = why.empty() ? "OpenImageIO could not read all of its pixels"
                      : why.substr(0, why.find('\n'));  // one line per failed strip
    std::snprintf(error, errorSize, "%s", why.c_str());
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return 1;
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_read), GlintOiioTextureRead>);

extern "C" __attribute__((visibility("default"))) void glint_oiio_texture_close(void* handle) {
  delete static_cast<OpenedImage*>(handle);
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_close), GlintOiioTextureClose>);
