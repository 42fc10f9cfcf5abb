// libglint_oiio.so: the only code linked against OpenImageIO (film/oiio_module.h).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <list>
#include <memory>
#include <mutex>
#include <string>
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

// One TextureSystem for the process: it owns the cache of mip-mapped tiles every lookup shares.
OIIO::TextureSystem& textureSystem() {
  static OIIO::TextureSystem* const ts = [] {
    OIIO::TextureSystem* t = OIIO::TextureSystem::create(/*shared=*/false);
    // Untiled, un-mip-mapped files (every PNG and JPEG) are read whole once and mip-mapped in
    // memory; colours stay as the file stores them, not premultiplied by alpha (a cut-out's
    // edge keeps its colour).
    t->attribute("automip", 1);
    t->attribute("unassociatedalpha", 1);
    t->attribute("max_memory_MB", 1024.0f);
    return t;
  }();
  return *ts;
}

// Whether every mip level the file `name` holds reads whole (`proxy`: its bytes, for an image
// held in memory); else `why` says what failed. OpenImageIO's TIFF reader reports a truncated
// file's missing strips as errors yet says it succeeded, and the TextureSystem then rendered
// them black without a word; so the file is read once when opened, in bands of about 16 MB,
// and any error its reader reports refuses it.
bool readsWhole(const char* name, OIIO::Filesystem::IOProxy* proxy, std::string& why) {
  OIIO::ImageSpec config;
  if (proxy) config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name, &config);
  if (!in) {
    why = OIIO::geterror();
    return false;
  }
  std::vector<float> band;
  for (int level = 0; in->seek_subimage(0, level); ++level) {
    const OIIO::ImageSpec spec = in->spec();
    const size_t row = size_t(std::max(spec.width, 1)) * size_t(std::max(spec.nchannels, 1));
    const int rows =
        int(std::clamp<size_t>((size_t{4} << 20) / row, 1, size_t(std::max(spec.height, 1))));
    band.resize(row * size_t(rows));
    for (int z = spec.z; z < spec.z + std::max(spec.depth, 1); ++z)
      for (int y = spec.y; y < spec.y + spec.height; y += rows)
        if (!in->read_scanlines(0, level, y, std::min(y + rows, spec.y + spec.height), z, 0,
                                spec.nchannels, OIIO::TypeDesc::FLOAT, band.data()) ||
            in->has_error()) {
          why = in->geterror();
          why = why.empty() ? "OpenImageIO could not read all of its pixels"
                            : why.substr(0, why.find('\n'));  // one line per failed strip
          return false;
        }
  }
  if (in->has_error()) {
    why = in->geterror();
    return false;
  }
  return true;
}

// A texture's handle and what the caller needs of its header; null with OpenImageIO's message.
void* openHandle(const char* name, GlintOiioTextureInfo* info, char* error, size_t errorSize) {
  {
    OIIO::TextureSystem& ts = textureSystem();
    OIIO::TextureSystem::TextureHandle* handle = ts.get_texture_handle(OIIO::ustring(name));
    const OIIO::ImageSpec* spec = handle ? ts.imagespec(handle, nullptr) : nullptr;
    if (!spec) {
      std::snprintf(error, errorSize, "%s", ts.geterror().c_str());
      return nullptr;
    }

    info->width = spec->width;
    info->height = spec->height;
    info->channels = spec->nchannels;
    info->isFloat = spec->format.is_floating_point();
    info->bytesPerChannel = int(spec->format.size());
    std::snprintf(info->colorspace, sizeof info->colorspace, "%s",
                  spec->get_string_attribute("oiio:ColorSpace").c_str());
    return handle;
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void* glint_oiio_texture_open(
    const char* path, GlintOiioTextureInfo* info, char* error, size_t errorSize) {
  try {
    if (std::string why; !readsWhole(path, nullptr, why)) {
      std::snprintf(error, errorSize, "%s", why.c_str());
      return nullptr;
    }
    return openHandle(path, info, error, errorSize);
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return nullptr;
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_open), GlintOiioTextureOpen>);

extern "C" __attribute__((visibility("default"))) void* glint_oiio_texture_open_memory(
    const char* name, const void* bytes, size_t size, GlintOiioTextureInfo* info, char* error,
    size_t errorSize) {
  try {
    // The cache reads the image through a memory proxy, which (with its bytes) must outlive
    // every lookup: kept until the process ends.
    struct Held {
      std::vector<unsigned char> bytes;
      std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
    };
    static std::mutex mutex;
    static std::list<Held> held;
    OIIO::Filesystem::IOProxy* proxy = nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      Held& h = held.emplace_back();
      h.bytes.assign(static_cast<const unsigned char*>(bytes),
                     static_cast<const unsigned char*>(bytes) + size);
      h.proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(h.bytes.data(), h.bytes.size());
      proxy = h.proxy.get();
    }
    // Checked through a proxy of its own: the cache's keeps its own read position.
    OIIO::Filesystem::IOMemReader check(bytes, size);
    if (std::string why; !readsWhole(name, &check, why)) {
      std::snprintf(error, errorSize, "%s", why.c_str());
      return nullptr;
    }
    OIIO::ImageSpec config;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    textureSystem().imagecache()->add_file(OIIO::ustring(name), nullptr, &config);
    return openHandle(name, info, error, errorSize);
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return nullptr;
}
static_assert(
    std::is_same_v<decltype(&glint_oiio_texture_open_memory), GlintOiioTextureOpenMemory>);

extern "C" __attribute__((visibility("default"))) int glint_oiio_texture_lookup(
    void* handle, const float* st, const float* axes, const int* wrap, int firstChannel,
    int channels, float* out) {
  OIIO::TextureSystem& ts = textureSystem();
  thread_local OIIO::TextureSystem::Perthread* const perThread = ts.get_perthread_info();
  const auto oiioWrap = [](int w) {
    return w == kGlintOiioWrapClamp    ? OIIO::TextureOpt::WrapClamp
           : w == kGlintOiioWrapMirror ? OIIO::TextureOpt::WrapMirror
                                       : OIIO::TextureOpt::WrapPeriodic;
  };
  OIIO::TextureOpt options;
  options.swrap = oiioWrap(wrap[0]);
  options.twrap = oiioWrap(wrap[1]);
  options.firstchannel = firstChannel;
  return ts.texture(static_cast<OIIO::TextureSystem::TextureHandle*>(handle), perThread, options,
                    st[0], st[1], axes[0], axes[1], axes[2], axes[3], channels, out)
             ? 0
             : 1;
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_lookup), GlintOiioTextureLookup>);

extern "C" __attribute__((visibility("default"))) int glint_oiio_texture_texels(
    void* handle, int width, int y0, int y1, int channels, float* out, char* error,
    size_t errorSize) {
  try {
    OIIO::TextureSystem& ts = textureSystem();
    thread_local OIIO::TextureSystem::Perthread* const perThread = ts.get_perthread_info();
    ts.geterror();
    OIIO::TextureOpt options;
    if (ts.get_texels(static_cast<OIIO::TextureSystem::TextureHandle*>(handle), perThread, options,
                      0, 0, width, y0, y1, 0, 1, 0, channels, OIIO::TypeFloat, out))
      return 0;
    const std::string message = ts.geterror();
    std::snprintf(error, errorSize, "%s",
                  message.empty() ? "OpenImageIO could not read its texels" : message.c_str());
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return 1;
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_texels), GlintOiioTextureTexels>);

extern "C" __attribute__((visibility("default"))) int glint_oiio_texture_load(void* handle,
                                                                              int channels,
                                                                              char* error,
                                                                              size_t errorSize) {
  try {
    OIIO::TextureSystem& ts = textureSystem();
    ts.geterror();  // the messages of earlier textures are theirs
    float texel[4] = {0, 0, 0, 0};
    const float st[2] = {0.5f, 0.5f}, axes[4] = {0, 0, 0, 0};
    const int wrap[2] = {kGlintOiioWrapRepeat, kGlintOiioWrapRepeat};
    const int looked =
        glint_oiio_texture_lookup(handle, st, axes, wrap, 0, std::min(channels, 4), texel);
    const std::string message = ts.geterror();
    if (looked == 0 && message.empty()) return 0;
    std::snprintf(error, errorSize, "%s",
                  message.empty() ? "OpenImageIO could not read its texels" : message.c_str());
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
  }
  return 1;
}
static_assert(std::is_same_v<decltype(&glint_oiio_texture_load), GlintOiioTextureLoad>);
