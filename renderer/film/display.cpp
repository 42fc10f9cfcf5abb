#include "film/display.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "film/atomic_file.h"

namespace glint {

float srgbEncode(float x) {
  if (!(x > 0)) return 0;  // also maps NaN to 0
  if (x >= 1) return 1;
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1 / 2.4f) - 0.055f;
}

void writeDisplayPng(const std::string& path, const Film& film) {
  const PixelWindow& w = film.window();
  std::vector<unsigned char> bytes(static_cast<size_t>(w.area()) * 3);
  size_t i = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x) {
      const double* p = film.pixel(x, y);
      for (int c = 0; c < 3; ++c)
        bytes[i++] =
            static_cast<unsigned char>(std::lround(255.0f * srgbEncode(static_cast<float>(p[c]))));
    }
  OIIO::ImageSpec spec(w.width(), w.height(), 3, OIIO::TypeDesc::UINT8);
  writeFileAtomically(path, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw GlintError("cannot write " + path + ": " + OIIO::geterror());
    if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) ||
        !out->close())
      throw GlintError("cannot write " + path + ": " + out->geterror());
  });
}

}  // namespace glint
