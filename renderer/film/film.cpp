#include "film/film.h"

#include <utility>

#include "core/check.h"

namespace glint {

Film::Film(int fullWidth, int fullHeight, const PixelWindow& window, FilmPixels pixels)
    : fullWidth_(fullWidth), fullHeight_(fullHeight), window_(window) {
  GLINT_CHECK(window.x0 >= 0 && window.x1 <= fullWidth && window.x0 < window.x1);
  GLINT_CHECK(window.y0 >= 0 && window.y1 <= fullHeight && window.y0 < window.y1);
  const size_t values = static_cast<size_t>(window.area()) * 4;
  if (pixels == FilmPixels::Zeroed)
    rgba_.assign(values, 0.0);
  else
    rgba_.resize(values);
}

size_t Film::offset(int x, int y) const {
  return (static_cast<size_t>(y - window_.y0) * static_cast<size_t>(window_.width()) +
          static_cast<size_t>(x - window_.x0)) *
         4;
}

void Film::setPixel(int x, int y, double r, double g, double b, double a) {
  double* p = &rgba_[offset(x, y)];
  p[0] = r;
  p[1] = g;
  p[2] = b;
  p[3] = a;
}

const double* Film::pixel(int x, int y) const { return &rgba_[offset(x, y)]; }

std::vector<float> Film::toFloatRgba() const {
  std::vector<float> out(rgba_.size());
  for (size_t i = 0; i < rgba_.size(); ++i) out[i] = static_cast<float>(rgba_[i]);
  return out;
}

size_t Film::addPlane(std::string name, std::vector<std::string> channels, bool isUint) {
  FilmPlane p{std::move(name), std::move(channels), isUint, {}};
  p.values.assign(static_cast<size_t>(window_.area()) * p.channels.size(), 0.0);
  planes_.push_back(std::move(p));
  return planes_.size() - 1;
}

void Film::setPlanePixel(size_t plane, int x, int y, const double* values) {
  double* p = planePixel(plane, x, y);
  for (size_t c = 0; c < planes_[plane].channels.size(); ++c) p[c] = values[c];
}

double* Film::planePixel(size_t plane, int x, int y) {
  FilmPlane& p = planes_[plane];
  return &p.values[offset(x, y) / 4 * p.channels.size()];
}

const double* Film::planePixel(size_t plane, int x, int y) const {
  const FilmPlane& p = planes_[plane];
  return &p.values[offset(x, y) / 4 * p.channels.size()];
}

namespace {
template <class T>
void setAttribute(std::vector<std::pair<std::string, T>>& attributes, const std::string& key,
                  T value) {
  for (auto& [k, v] : attributes)
    if (k == key) {
      v = std::move(value);
      return;
    }
  attributes.emplace_back(key, std::move(value));
}
}  // namespace

void Film::addAttribute(const std::string& key, std::string value) {
  setAttribute(stringAttributes_, key, std::move(value));
}

void Film::addAttribute(const std::string& key, int value) {
  setAttribute(intAttributes_, key, value);
}

}  // namespace glint
