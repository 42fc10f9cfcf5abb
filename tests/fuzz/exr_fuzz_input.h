#pragma once
// The oracle of glint_fuzz_exr, shared with its regression test
// (tests/io/input_fuzz_regression_test.cpp): an EXR file goes to readImage (glint compare,
// convert, converge), to readFrameRecord and mergeCrops (glint merge) as the one crop of a
// frame, and to readResumeState (glint render --resume) for the window it declares. A merged
// frame must hold no Inf or NaN: Glint writes none, and merge refuses a crop that does.
#include <OpenEXR/ImfChannelList.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_files.h"
#include "core/sampler.h"
#include "film/exr_input.h"
#include "film/exr_output.h"
#include "film/merge.h"
#include "render/frame_record.h"

namespace glint::fuzz {

// "" when every value of part 0 of `path` (each channel read as float) is finite, else which is
// not.
inline std::string nonFiniteValueIn(const std::string& path) {
  const auto file = openExr(path);
  // Reading it makes it an input of this process, and the next input's merge writes it again.
  allowReplacingInput(path);
  std::vector<ExrSlice> slices;
  const Imf::ChannelList& channels = file->header(0).channels();
  for (auto c = channels.begin(); c != channels.end(); ++c)
    slices.push_back({c.name(), Imf::FLOAT, sizeof(float) * slices.size()});
  std::vector<float> values;
  readPixelsInBands(path, *file, 0, slices, sizeof(float) * slices.size(), values);
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      return "mergeCrops wrote a non-finite " + slices[i % slices.size()].name + " value";
  return "";
}

// "" when every reader gives an acceptable outcome (an image whose pixel array matches its size,
// a merged frame of finite values, a resume state a render could leave, or a GlintError naming the
// file), else what is wrong. `mergedPath` receives the merge's output. Any other exception
// propagates: that is a bug too.
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
    (void)mergeCrops(mergedPath, {cropRecord(path)}, "glint merge (fuzz)");
    if (const std::string p = nonFiniteValueIn(mergedPath); !p.empty()) return p;
  } catch (const GlintError& e) {
    if (const std::string p = namesFile(e); !p.empty()) return p;
  }
  try {
    // The window the file declares, so that the reader goes on to its channels and pixels; at
    // most 2^20 samples a pixel, as a --spp that large would allow. What it accepts must be a
    // state a render could leave (resume_state.h): finite means, coverage within [0, count],
    // at least a ray a sample and at most 2^62 a half (none without samples), counts within the
    // limit and split between the halves as a render splits them.
    constexpr int64_t kMaxSamples = int64_t{1} << 20;
    const ExrWindow w = exrWindow(path, openExr(path)->header(0));
    const PixelWindow window{w.x, w.x + w.width, w.y, w.y + w.height};
    const ResumeState state = readResumeState(path, window, w.fullWidth, w.fullHeight, kMaxSamples);
    const PassPosition& at = state.position;
    if (state.estimates.size() != size_t(window.area()) ||
        (at.cutEnd > 0 && at.cutChosen.size() != state.estimates.size()))
      return "readResumeState: " + std::to_string(state.estimates.size()) + " pixels for " +
             std::to_string(w.width) + "x" + std::to_string(w.height);
    for (size_t i = 0; i < state.estimates.size(); ++i) {
      const PixelEstimate& p = state.estimates[i];
      const bool chosen = at.cutEnd > 0 && at.cutChosen[i] == 1;
      bool valid = p.samples() <= kMaxSamples && halfSampleCount(p.samples(), 0) == p.half[0].count;
      // No pixel past the passes the frame finished, but for one the cut pass had chosen.
      valid = valid && (p.samples() <= at.finishedEnd || (chosen && p.samples() <= at.cutEnd));
      for (const HalfEstimate& h : p.half) {
        valid = valid && h.count >= 0 && h.alpha >= 0 && h.alpha <= h.count &&
                h.rays >= uint64_t(h.count) && h.rays <= uint64_t{1} << 62 &&
                (h.count > 0 || h.rays == 0);
        for (double m : h.mean) valid = valid && std::isfinite(m);
      }
      if (!valid) return "readResumeState accepted a state no render leaves";
    }
  } catch (const GlintError& e) {
    return namesFile(e);
  }
  return "";
}

}  // namespace glint::fuzz
