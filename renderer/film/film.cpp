#include "film/film.h"

#include <cmath>
#include <limits>
#include <utility>

#include "core/check.h"

namespace glint {

Film::Film(int fullWidth, int fullHeight, const PixelWindow& window, FilmPixels pixels)
    : fullWidth_(fullWidth), fullHeight_(fullHeight), window_(window) {
  GLINT_CHECK(window.x0 >= 0 && window.x1 <= fullWidth && window.x0 < window.x1);
  GLINT_CHECK(window.y0 >= 0 && window.y1 <= fullHeight && window.y0 < window.y1);
  const size_t values = static_cast<size_t>(window.area()) * 4;
  if (pixels == FilmPixels::Zeroed)
    rgba_.assign(values, 0.0f);
  else
    rgba_.resize(values);
}

size_t Film::offset(int x, int y) const {
  return (static_cast<size_t>(y - window_.y0) * static_cast<size_t>(window_.width()) +
          static_cast<size_t>(x - window_.x0)) *
         4;
}

namespace {
// `v` in float; past float's largest finite value an infinity of its sign, where rounding to
// nearest would give that largest value to the values within half a unit above it.
float toFilmValue(double v) {
  constexpr double kLargest = std::numeric_limits<float>::max();
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  if (std::abs(v) > kLargest) return v > 0 ? kInfinity : -kInfinity;
  return static_cast<float>(v);
}
}  // namespace

void Film::setPixel(int x, int y, double r, double g, double b, double a) {
  float* p = &rgba_[offset(x, y)];
  p[0] = toFilmValue(r);
  p[1] = toFilmValue(g);
  p[2] = toFilmValue(b);
  p[3] = toFilmValue(a);
}

const float* Film::pixel(int x, int y) const { return &rgba_[offset(x, y)]; }

std::vector<float> Film::toFloatRgba() const { return {rgba_.begin(), rgba_.end()}; }

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
