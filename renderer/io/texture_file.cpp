#include "io/texture_file.h"

#include <algorithm>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string_view>

#include "core/error.h"
#include "core/input_files.h"
#include "core/memory.h"
#include "core/out_of_memory.h"
#include "film/display.h"
#include "film/image_limits.h"
#include "film/oiio_module.h"

namespace glint {

namespace {

// What reading a texture takes, in multiples of its texels in their own type (above).
constexpr double kTextureCopies = 3;

void throwIfOutOfMemory(const char* error);

class TextureFile final : public ImageTexture {
 public:
  TextureFile(std::string path, void* handle, const GlintOiioTextureInfo& info,
              const std::string& colorspace, const oiio_module::TextureFunctions& functions)
      : path_(std::move(path)),
        handle_(handle),
        channels_(info.channels),
        width_(info.width),
        height_(info.height),
        toRendering_(colorspace),
        lookup_(functions.lookup),
        texels_(functions.texels) {}

  Rgb color(const ImageFootprint& at) const override {
    float texel[3] = {0, 0, 0};
    if (!readRgb(at, texel)) return {};
    if (!toRendering_.isIdentity()) toRendering_.apply(texel);
    return {texel[0], texel[1], texel[2]};
  }

  Rgb data(const ImageFootprint& at) const override {
    float texel[3] = {0, 0, 0};
    if (!readRgb(at, texel)) return {};
    return {texel[0], texel[1], texel[2]};
  }

  float coverage(const ImageFootprint& at, bool greyWithoutAlpha) const override {
    // RGBA's fourth channel, grey-alpha's second; else the first, or opaque.
    const int channel = channels_ == 4 ? 3 : channels_ == 2 ? 1 : greyWithoutAlpha ? 0 : -1;
    float a = 1;
    if (channel >= 0 && !read(at, channel, 1, &a)) return 1;
    return a;
  }

  const std::string& path() const override { return path_; }

  LatLongImage texels(double bytesPerTexel) const {
    const double count = double(width_) * double(height_);
    checkMemoryFits(count * bytesPerTexel, "image " + path_ + " (" + std::to_string(width_) + "x" +
                                               std::to_string(height_) + ", read whole)");
    LatLongImage image;
    image.width = width_;
    image.height = height_;
    image.texels.resize(static_cast<size_t>(count));
    const int colorChannels = channels_ >= 3 ? 3 : 1;
    // A band of rows at a time: the floats in the file's layout are never all held at once.
    constexpr int kBandRows = 16;
    std::vector<float> band(static_cast<size_t>(width_) * kBandRows *
                            static_cast<size_t>(colorChannels));
    size_t next = 0;
    for (int y0 = 0; y0 < height_; y0 += kBandRows) {
      const int y1 = std::min(height_, y0 + kBandRows);
      char error[512] = "";
      if (texels_(handle_, width_, y0, y1, colorChannels, band.data(), error, sizeof error) != 0) {
        throwIfOutOfMemory(error);
        throw GlintError("cannot read image " + path_ + ": " + excerpt(error));
      }
      const size_t n = static_cast<size_t>(width_) * static_cast<size_t>(y1 - y0);
      for (size_t i = 0; i < n; ++i) {
        const float* f = band.data() + i * static_cast<size_t>(colorChannels);
        float texel[3] = {f[0], colorChannels == 3 ? f[1] : f[0], colorChannels == 3 ? f[2] : f[0]};
        if (!toRendering_.isIdentity()) toRendering_.apply(texel);
        image.texels[next++] = {texel[0], texel[1], texel[2]};
      }
    }
    return image;
  }

 private:
  // Grey (and grey-alpha) images give their one colour channel to all three.
  bool readRgb(const ImageFootprint& at, float* texel) const {
    const int colorChannels = channels_ >= 3 ? 3 : 1;
    if (!read(at, 0, colorChannels, texel)) return false;
    if (colorChannels == 1) texel[1] = texel[2] = texel[0];
    return true;
  }
  bool read(const ImageFootprint& at, int first, int count, float* out) const {
    const float st[2] = {at.st.x, at.st.y};
    const float axes[4] = {at.axisA.x, at.axisA.y, at.axisB.x, at.axisB.y};
    const int wrap[2] = {oiioWrap(at.wrapS), oiioWrap(at.wrapT)};
    // A file that fails mid-render (it was read whole when opened, so only a cache eviction
    // and a changed file could) gives black: the per-ray path never throws.
    return lookup_(handle_, st, axes, wrap, first, count, out) == 0;
  }

  static int oiioWrap(TextureWrap w) {
    return w == TextureWrap::ClampToEdge      ? kGlintOiioWrapClamp
           : w == TextureWrap::MirroredRepeat ? kGlintOiioWrapMirror
                                              : kGlintOiioWrapRepeat;
  }

  std::string path_;
  void* handle_;
  int channels_, width_, height_;
  ToRenderingSpace toRendering_;
  GlintOiioTextureLookup lookup_;
  GlintOiioTextureTexels texels_;
};

}  // namespace

std::string defaultTextureColorspace(bool floatTexels, const std::string& declared) {
  if (floatTexels) return kRenderingColorspace;
  for (const char* linear : {"linear", "Linear", "scene_linear", "lin_rec709"})
    if (declared == linear) return kRenderingColorspace;
  return "sRGB - Texture";
}

namespace {

// The module passes exceptions back as their text: a failed allocation or a thread that could
// not start is the machine's failure (exit 1, named by whileDoing), not a texture to leave out.
void throwIfOutOfMemory(const char* error) {
  if (std::string_view(error) == std::bad_alloc().what()) throw std::bad_alloc();
  if (*error && out_of_memory::isResourceShortage(std::runtime_error(error)))
    throw std::runtime_error(error);
}

// The texture behind a handle the module opened (null: it could not, `error` says why), checked
// and read once.
std::shared_ptr<const ImageTexture> checkedTexture(const std::string& path, void* handle,
                                                   const GlintOiioTextureInfo& info,
                                                   const char* error, const std::string& colorspace,
                                                   const oiio_module::TextureFunctions& functions) {
  if (!handle) {
    throwIfOutOfMemory(error);
    throw GlintError("cannot read texture " + path + ": " + excerpt(error));
  }
  if (info.channels < 1) throw GlintError("texture " + path + " has no channels");
  // Only the header is read so far. The TextureSystem reads an untiled file whole and mip-maps
  // it in memory: its texels in their own type twice (the file's read and the cache's copy),
  // the smaller levels and the working space of its threads (docs/hardening.md, "Memory")
  // come to about three times them. That must fit before
  // any is read, since OpenImageIO, failing to allocate it, goes on decoding the whole file
  // again for every tile, for hours.
  const int bytesPerChannel = std::max(info.bytesPerChannel, 1);
  checkMemoryFits(
      kTextureCopies * double(info.width) * double(info.height) * info.channels * bytesPerChannel,
      "texture " + path + " (" + std::to_string(info.width) + "x" + std::to_string(info.height) +
          ", " + std::to_string(info.channels) + " channels of " + std::to_string(bytesPerChannel) +
          (bytesPerChannel == 1 ? " byte" : " bytes") + ", read, cached and MIP-mapped)");
  // An empty size, or one past what a process can address, where the budget is unknown.
  checkImageFits(path, "texture", info.width, info.height,
                 4.0 / 3 * bytesPerChannel * info.channels);
  auto texture = std::make_shared<TextureFile>(
      path, handle, info,
      colorspace.empty() ? defaultTextureColorspace(info.isFloat != 0, info.colorspace)
                         : colorspace,
      functions);
  // Reading it now (and building its mip levels) refuses a truncated or corrupt image here, with
  // its reason, instead of rendering black.
  char loadError[512] = "";
  if (functions.load(handle, info.channels, loadError, sizeof loadError) != 0) {
    throwIfOutOfMemory(loadError);
    throw GlintError("cannot read texture " + path + ": " + excerpt(loadError));
  }
  return texture;
}

std::shared_ptr<const ImageTexture> openTextureFile(const std::string& path,
                                                    const std::string& colorspace) {
  checkInputFile(path, kMaxTextureFileBytes, "texture");
  const oiio_module::TextureFunctions& functions = oiio_module::textureFunctions(path);
  GlintOiioTextureInfo info{};
  char error[512] = "";
  void* handle = functions.open(path.c_str(), &info, error, sizeof error);
  return checkedTexture(path, handle, info, error, colorspace, functions);
}

std::shared_ptr<const ImageTexture> openTextureBytes(const std::string& name,
                                                     const std::string& bytes) {
  const oiio_module::TextureFunctions& functions = oiio_module::textureFunctions(name);
  GlintOiioTextureInfo info{};
  char error[512] = "";
  void* handle =
      functions.openMemory(name.c_str(), bytes.data(), bytes.size(), &info, error, sizeof error);
  return checkedTexture(name, handle, info, error, "", functions);
}

}  // namespace

std::shared_ptr<const ImageTexture> openImageTexture(const std::string& path,
                                                     const std::string& colorspace) {
  return out_of_memory::whileDoing("reading texture " + path,
                                   [&] { return openTextureFile(path, colorspace); });
}

LatLongImage readTexels(const ImageTexture& texture, double bytesPerTexel) {
  const auto* file = dynamic_cast<const TextureFile*>(&texture);
  if (!file) throw GlintError("texture " + texture.path() + " is not read from an image file");
  return out_of_memory::whileDoing("reading image " + texture.path(),
                                   [&] { return file->texels(bytesPerTexel); });
}

std::shared_ptr<const ImageTexture> openImageTextureInMemory(const std::string& name,
                                                             const std::string& bytes) {
  return out_of_memory::whileDoing("reading texture " + name,
                                   [&] { return openTextureBytes(name, bytes); });
}

}  // namespace glint
