#include "film/rgb_channels.h"

#include "core/error.h"

namespace glint {

namespace {

// Whether channel `c` is `name` of the layer `layer` ("" or "beauty.").
bool is(const Image& image, size_t c, char name, const std::string& layer) {
  if (c >= image.channelNames.size()) return false;
  return image.channelNames[c] == layer + name;
}

std::string layerOf(const Image& image) {
  if (image.channelNames.empty()) return {};
  const std::string& first = image.channelNames[0];
  return first.substr(0, first.size() - 1);
}

}  // namespace

void requireRgb(const Image& image, const std::string& path, const std::string& command) {
  const std::string layer = layerOf(image);
  if ((layer.empty() || layer.back() == '.') && is(image, 0, 'R', layer) &&
      is(image, 1, 'G', layer) && is(image, 2, 'B', layer))
    return;
  std::string names;
  for (const std::string& n : image.channelNames) names += (names.empty() ? "" : ", ") + n;
  throw UsageError(path + ": " + command + " needs R, G and B channels; it has " +
                   excerpt(names.empty() ? "none" : names));
}

bool hasAlpha(const Image& image) { return is(image, 3, 'A', layerOf(image)); }

}  // namespace glint
