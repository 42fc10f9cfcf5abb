#include "io/texture_file.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string_view>

#include "core/error.h"
#include "core/input_files.h"
#include "core/log.h"
#include "core/memory.h"
#include "core/out_of_memory.h"
#include "film/display.h"
#include "film/image_limits.h"
#include "film/oiio_module.h"
#include "io/own_texture_readers.h"
#include "io/psd_sections.h"
#include "io/texture_formats.h"
#include "materials/mip_pyramid.h"

namespace glint {

namespace {

void throwIfOutOfMemory(const char* error);

// The channels kept of a file's: all of grey, grey-alpha, RGB and RGBA; the colour of more.
int keptChannels(int fileChannels) { return fileChannels <= 4 ? fileChannels : 3; }

class TextureFile final : public ImageTexture {
 public:
  TextureFile(std::string path, int fileChannels, MipPyramid pyramid,
              std::unique_ptr<const ToRenderingSpace> toRendering, size_t negative)
      : path_(std::move(path)),
        fileChannels_(fileChannels),
        pyramid_(std::move(pyramid)),
        toRendering_(std::move(toRendering)),
        negative_(negative) {}

  Rgb color(const ImageFootprint& at) const override {
    float texel[3];
    readRgb(at, texel);
    if (negative_ > 0) [[unlikely]]
      clampNegative(texel);
    if (!toRendering_->isIdentity()) toRendering_->apply(texel);
    return {texel[0], texel[1], texel[2]};
  }

  Rgb data(const ImageFootprint& at) const override {
    float texel[3];
    readRgb(at, texel);
    return {texel[0], texel[1], texel[2]};
  }

  float coverage(const ImageFootprint& at, bool greyWithoutAlpha) const override {
    // RGBA's fourth channel, grey-alpha's second; else the first, or opaque.
    const int channel = fileChannels_ == 4 ? 3 : fileChannels_ == 2 ? 1 : greyWithoutAlpha ? 0 : -1;
    if (channel < 0) return 1;
    float a;
    pyramid_.filter(at, channel, 1, &a);
    return a;
  }

  const std::string& path() const override { return path_; }

  LatLongImage texels(double bytesPerTexel) const {
    const int width = pyramid_.width(), height = pyramid_.height();
    const double count = double(width) * double(height);
    checkMemoryFits(count * bytesPerTexel, "image " + path_ + " (" + std::to_string(width) + "x" +
                                               std::to_string(height) + ", read whole)");
    LatLongImage image;
    image.width = width;
    image.height = height;
    image.texels.resize(static_cast<size_t>(count));
    const size_t stride = size_t(pyramid_.channels());
    const bool grey = pyramid_.channels() < 3;
    const float* f = pyramid_.texels().data();
    for (Rgb& out : image.texels) {
      float texel[3] = {f[0], grey ? f[0] : f[1], grey ? f[0] : f[2]};
      if (!toRendering_->isIdentity()) toRendering_->apply(texel);
      out = {texel[0], texel[1], texel[2]};
      f += stride;
    }
    return image;
  }

 private:
  // Grey (and grey-alpha) images give their one colour channel to all three.
  void readRgb(const ImageFootprint& at, float* texel) const {
    if (pyramid_.channels() >= 3) {
      pyramid_.filter(at, 0, 3, texel);
    } else {
      pyramid_.filter(at, 0, 1, texel);
      texel[1] = texel[2] = texel[0];
    }
  }

  std::string path_;
  int fileChannels_;
  MipPyramid pyramid_;
  // A colour filtered from negative texels counts as 0 in each such channel, and the first
  // lookup that gives a colour says so once (as data, a normal map's, they are meaningful).
  void clampNegative(float* texel) const {
    for (int c = 0; c < 3; ++c) texel[c] = std::max(texel[c], 0.0f);
    if (!warnedNegative_.exchange(true, std::memory_order_relaxed))
      log::warning("texture " + path_ + ": " + std::to_string(negative_) +
                   " colour values are negative; as a colour the image is read with them as 0");
  }

  std::unique_ptr<const ToRenderingSpace> toRendering_;
  size_t negative_;  // the colour channels' negative values in the file
  mutable std::atomic<bool> warnedNegative_{false};
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

// The texture behind a handle the module opened (null: it could not, `error` says why): its
// full-resolution texels read whole into floats and made a MIP pyramid. OpenImageIO only reads
// the file; Glint filters (materials/mip_pyramid.h), so lookups call no library and share no
// lock.
std::shared_ptr<const ImageTexture> loadedTexture(const std::string& path, void* handle,
                                                  const GlintOiioTextureInfo& info,
                                                  const char* error, const std::string& colorspace,
                                                  const oiio_module::TextureFunctions& functions) {
  if (!handle) {
    throwIfOutOfMemory(error);
    throw GlintError("cannot read texture " + path + ": " + excerpt(error));
  }
  const std::unique_ptr<void, GlintOiioTextureClose> opened(handle, functions.close);
  if (info.channels < 1) throw GlintError("texture " + path + " has no channels");
  const int channels = keptChannels(info.channels);
  // Only the header is read so far. The pyramid holds the kept channels in float, 4/3 of the
  // finest level's texels (or up to twice them for a strip), and OpenImageIO reads a band of
  // rows in the file's type beside it: that must fit before any texel is read.
  const int bytesPerChannel = std::max(info.bytesPerChannel, 1);
  // About 4 MB of floats, whole tiles of a tiled file.
  const int64_t tile = std::max(info.tileHeight, 1);
  const int bandRows = int(std::clamp<int64_t>(
      (int64_t{4} << 20) / std::max<int64_t>(int64_t{info.width} * channels * 4, 1) / tile * tile,
      tile, std::max<int64_t>(info.height, tile)));
  const double bandBytes =
      double(info.width) * bandRows * double(info.channels) * double(bytesPerChannel + 4);
  checkMemoryFits(
      MipPyramid::bytesFor(info.width, info.height, channels) + bandBytes,
      "texture " + path + " (" + std::to_string(info.width) + "x" + std::to_string(info.height) +
          ", " + std::to_string(info.channels) + " channels of " + std::to_string(bytesPerChannel) +
          (bytesPerChannel == 1 ? " byte" : " bytes") + ", read into a MIP pyramid of floats)");
  // An empty size, or one past what a process can address, where the budget is unknown.
  checkImageFits(path, "texture", info.width, info.height, 4.0 / 3 * 4 * channels);
  auto toRendering = std::make_unique<const ToRenderingSpace>(
      colorspace.empty() ? defaultTextureColorspace(info.isFloat != 0, info.colorspace)
                         : colorspace);
  // Reading it whole now refuses a truncated or corrupt image here, with its reason, instead
  // of rendering black.
  const size_t row = size_t(info.width) * size_t(channels);
  std::vector<float> texels;
  texels.reserve(row * size_t(info.height) + 1);  // with the pyramid's padding float
  for (int y0 = 0; y0 < info.height; y0 += bandRows) {
    const int y1 = std::min(info.height, y0 + bandRows);
    // Grown (and so written) a band at a time: a small file declaring a huge image fails at its
    // first missing band, having touched what was read, not the whole declared size.
    texels.resize(row * size_t(y1));
    char readError[512] = "";
    if (functions.read(handle, y0, y1, channels, texels.data() + row * size_t(y0), readError,
                       sizeof readError) != 0) {
      throwIfOutOfMemory(readError);
      throw GlintError("cannot read texture " + path + ": " + excerpt(readError));
    }
  }
  // A float file may hold NaN or infinity, which the MIP filter would spread to every texel
  // that blends it and every pixel that sees them (an environment refuses them the same way).
  if (info.isFloat)
    for (size_t i = 0; i < texels.size(); ++i)
      if (!std::isfinite(texels[i]))
        throw GlintError("cannot read texture " + path + ": texel (" +
                         std::to_string(i / size_t(channels) % size_t(info.width)) + ", " +
                         std::to_string(i / row) + ") holds " +
                         (std::isnan(texels[i]) ? "NaN" : "an infinity") + " in channel " +
                         std::to_string(i % size_t(channels)) +
                         "; a texture's values must be finite");
  // Negative values are data (a normal map's), never a colour (TextureFile::clampNegative).
  size_t negative = 0;
  const int colourChannels = channels >= 3 ? 3 : 1;  // grey's one, not its alpha
  if (info.isFloat)
    for (size_t i = 0; i < texels.size(); i += size_t(channels))
      for (int c = 0; c < colourChannels; ++c) negative += texels[i + size_t(c)] < 0;
  return std::make_shared<TextureFile>(
      path, info.channels, MipPyramid(info.width, info.height, channels, std::move(texels)),
      std::move(toRendering), negative);
}

// Refuses a Photoshop file whose sections run past its end before OpenImageIO allocates them
// (io/psd_sections.h).
void checkPsdSections(const std::string& name, const ReadAt& read, uint64_t size) {
  if (const std::string why = psdSectionsPastTheEnd(read, size); !why.empty())
    throw GlintError("cannot read texture " + name + ": " + why);
}

std::shared_ptr<const ImageTexture> openTextureFile(const std::string& path,
                                                    const std::string& colorspace) {
  const uint64_t size = checkInputFile(path, kMaxTextureFileBytes, "texture");
  std::ifstream file(path, std::ios::binary);
  checkPsdSections(
      path,
      [&](uint64_t offset, char* out, size_t bytes) {
        return bool(file.seekg(std::streamoff(offset))) &&
               bool(file.read(out, std::streamsize(bytes)));
      },
      size);
  GlintOiioTextureInfo info{};
  char error[512] = "";
  // Glint's own readers first (each declines what is not its format): a scene whose textures
  // they all read never loads OpenImageIO's module.
  for (const OwnTextureReader* reader : kOwnTextureReaders) {
    bool declined = false;
    if (void* handle = reader->open(path, &info, error, sizeof error, &declined); !declined)
      return loadedTexture(path, handle, info, error, colorspace, reader->functions());
  }
  const std::string format = textureReaderFormat(path);
  const oiio_module::TextureFunctions& functions = oiio_module::textureFunctions(path);
  void* handle = functions.open(path.c_str(), format.c_str(), &info, error, sizeof error);
  return loadedTexture(path, handle, info, error, colorspace, functions);
}

std::shared_ptr<const ImageTexture> openTextureBytes(const std::string& name,
                                                     const std::string& bytes) {
  checkPsdSections(
      name,
      [&](uint64_t offset, char* out, size_t count) {
        if (offset > bytes.size() || count > bytes.size() - offset) return false;
        bytes.copy(out, count, size_t(offset));
        return true;
      },
      bytes.size());
  GlintOiioTextureInfo info{};
  char error[512] = "";
  for (const OwnTextureReader* reader : kOwnTextureReaders) {
    bool declined = false;
    if (void* handle = reader->openMemory(name, bytes.data(), bytes.size(), &info, error,
                                          sizeof error, &declined);
        !declined)
      return loadedTexture(name, handle, info, error, "", reader->functions());
  }
  const std::string format = textureReaderFormat(name);
  const oiio_module::TextureFunctions& functions = oiio_module::textureFunctions(name);
  void* handle = functions.openMemory(name.c_str(), format.c_str(), bytes.data(), bytes.size(),
                                      &info, error, sizeof error);
  return loadedTexture(name, handle, info, error, "", functions);
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
