#include "film/exr_output.h"

#include <OpenImageIO/imageio.h>

#include "core/error.h"
#include "film/atomic_file.h"

namespace glint {

const std::vector<std::string>& exrCompressions() {
  static const std::vector<std::string> names = {"none",  "rle", "zips", "zip",  "piz",
                                                 "pxr24", "b44", "b44a", "dwaa", "dwab"};
  return names;
}

void writeExr(const std::string& path, const Film& film, const ExrMetadata& meta,
              const ExrOptions& options) {
  const PixelWindow& w = film.window();
  OIIO::ImageSpec spec(w.width(), w.height(), 4,
                       options.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  spec.x = w.x0;
  spec.y = w.y0;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = film.fullWidth();
  spec.full_height = film.fullHeight();
  spec.channelnames = {"R", "G", "B", "A"};
  spec.alpha_channel = 3;
  spec.attribute("compression", options.compression);
  for (const auto& [k, v] : meta.strings) spec.attribute(k, v);
  for (const auto& [k, v] : meta.ints) spec.attribute(k, v);
  for (const auto& [k, v] : meta.floats) spec.attribute(k, v);
  for (const auto& [k, m] : meta.matrices) {
    float rowVector[16];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) rowVector[4 * c + r] = m(r, c);
    spec.attribute(k, OIIO::TypeMatrix44, rowVector);
  }
  const std::vector<float> pixels = film.toFloatRgba();

  writeFileAtomically(path, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) throw GlintError("OpenImageIO has no OpenEXR writer: " + OIIO::geterror());
    if (!out->open(tmp, spec)) throw GlintError("cannot write " + path + ": " + out->geterror());
    if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close())
      throw GlintError("cannot write " + path + ": " + out->geterror());
  });
}

Image readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw GlintError("cannot read " + path + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  img.x = spec.x;
  img.y = spec.y;
  img.fullWidth = spec.full_width;
  img.fullHeight = spec.full_height;
  img.pixels.resize(size_t(img.width) * size_t(img.height) * size_t(img.channels));
  if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    throw GlintError("cannot read " + path + ": " + in->geterror());
  return img;
}

}  // namespace glint
