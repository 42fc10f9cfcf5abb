#pragma once
// Shared by the texture readers' tests: a reader's rows read in bands, as io/texture_file.cpp
// reads them.
#include <algorithm>
#include <string>
#include <vector>

#include "film/oiio_module.h"

namespace glint::test {

// Reads the first `channels` channels of every row of the opened image `handle` (width ×
// height) into `texels` through `functions`, in bands of `bandRows` rows: false, with `error`,
// at the first band refused.
inline bool readInBands(const oiio_module::TextureFunctions& functions, void* handle, int width,
                        int height, int channels, int bandRows, std::vector<float>& texels,
                        std::string& error) {
  const size_t row = size_t(width) * size_t(channels);
  texels.assign(row * size_t(height), -1.0f);
  for (int y0 = 0, y1 = 0; y0 < height; y0 = y1) {
    y1 = y0 + std::min(bandRows, height - y0);
    char message[512] = "";
    if (functions.read(handle, y0, y1, channels, texels.data() + row * size_t(y0), message,
                       sizeof message) != 0) {
      error = message;
      return false;
    }
  }
  return true;
}

}  // namespace glint::test
