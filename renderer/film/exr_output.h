#pragma once
// Writes the film as an OpenEXR file through OpenImageIO: float RGBA (alpha = coverage), ZIP
// compression, data window = the crop inside the full display window, and Glint's metadata.
#include <string>
#include <utility>
#include <vector>

#include "film/film.h"

namespace glint {

struct ExrMetadata {
  std::vector<std::pair<std::string, std::string>> strings;  // e.g. {"glint:sampler", "..."}
  std::vector<std::pair<std::string, int>> ints;
  std::vector<std::pair<std::string, float>> floats;
};

void writeExr(const std::string& path, const Film& film, const ExrMetadata& meta);

// Reads an EXR's RGBA (full data window) as float; used by tests and `glint compare`.
struct Image {
  int width = 0, height = 0, channels = 0;
  int x = 0, y = 0, fullWidth = 0, fullHeight = 0;
  std::vector<float> pixels;
};
Image readImage(const std::string& path);

}  // namespace glint
