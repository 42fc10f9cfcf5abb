// libglint_oiio.so: the only code linked against OpenImageIO (film/oiio_module.h).
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <memory>
#include <type_traits>

#include "film/oiio_module_abi.h"

extern "C" __attribute__((visibility("default"))) int glint_oiio_write_image(
    const char* formatPath, const char* path, int width, int height, int channels, int bits,
    const void* pixels, char* error, size_t errorSize) {
  // No exception may cross this C boundary.
  try {
    const OIIO::TypeDesc type = bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
    const OIIO::ImageSpec spec(width, height, channels, type);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(formatPath);
    if (out && out->open(path, spec) && out->write_image(type, pixels) && out->close()) return 0;
    std::snprintf(error, errorSize, "%s", (out ? out->geterror() : OIIO::geterror()).c_str());
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return 1;
}
static_assert(std::is_same_v<decltype(&glint_oiio_write_image), GlintOiioWriteImage>);
