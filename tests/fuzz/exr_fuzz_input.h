#pragma once
// The oracle of glint_fuzz_exr, shared with its regression test
// (tests/io/input_fuzz_regression_test.cpp): an EXR file goes to readImage (glint compare,
// convert, converge) and to mergeCrops (glint merge) as the one crop of a frame.
#include <string>

#include "core/error.h"
#include "film/exr_output.h"
#include "film/merge.h"

namespace glint::fuzz {

// "" when both readers give an acceptable outcome (an image whose pixel array matches its size,
// a merged frame, or a GlintError naming the file), else what is wrong. `mergedPath` receives
// the merge's output. Any other exception propagates: that is a bug too.
inline std::string exrReadProblem(const std::string& path, const std::string& mergedPath) {
  const auto namesFile = [&](const GlintError& e) {
    return std::string(e.what()).find(path) != std::string::npos
               ? std::string()
               : std::string("an error that does not name the file: ") + e.what();
  };
  try {
    const Image img = readImage(path);
    if (img.pixels.size() != size_t(img.width) * size_t(img.height) * size_t(img.channels))
      return "readImage: " + std::to_string(img.pixels.size()) + " values for " +
             std::to_string(img.width) + "x" + std::to_string(img.height) + "x" +
             std::to_string(img.channels);
  } catch (const GlintError& e) {
    if (const std::string p = namesFile(e); !p.empty()) return p;
  }
  try {
    (void)mergeCrops(mergedPath, {path}, "glint merge (fuzz)");
  } catch (const GlintError& e) {
    return namesFile(e);
  }
  return "";
}

}  // namespace glint::fuzz
