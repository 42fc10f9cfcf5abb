// `glint compare A.exr B.exr`: error metrics of A against the reference B.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/log.h"
#include "film/atomic_file.h"
#include "film/compare.h"
#include "film/image_format.h"
#include "film/rgb_channels.h"

namespace glint {

nlohmann::json errorsJson(const ImageErrors& e) {
  const auto finite = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  return {{"rmse", finite(e.rmse)}, {"relmse", finite(e.relmse)},
          {"mae", finite(e.mae)},   {"max_abs", finite(e.maxAbs)},
          {"psnr", finite(e.psnr)}, {"share_above_threshold", e.aboveThreshold},
          {"pixels", e.pixels},     {"nonfinite_pixels", e.nonfinitePixels}};
}

CommandRunner addCompareCommand(CLI::App& app) {
  struct Args {
    std::string test, reference, diff, json;
    double threshold = kDefaultCompareThreshold;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("compare", "Error metrics between an image and a reference");
  cmd->add_option("image", a->test, "Image to measure (EXR)")->required()->check(CLI::ExistingFile);
  cmd->add_option("reference", a->reference, "Reference image (EXR)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--threshold", a->threshold,
                  "Per-pixel error counted in share_above_threshold (default " +
                      defaultText(a->threshold) + ")")
      ->check(positiveNumber());
  cmd->add_option("--diff", a->diff,
                  "Write a false-colour difference image (.png, .jpg or .tif, 8-bit)")
      ->check(nonEmpty());
  cmd->add_option("--json", a->json, "Write the figures as JSON")->check(nonEmpty());
  return [a] {
    if (!a->diff.empty()) imageOutputFormat("--diff", a->diff, ImageOutput::Display);
    // The inputs are noted first, so that an output naming one is refused before the work.
    noteInputFile(a->test);
    noteInputFile(a->reference);
    checkCommandOutputs({{"--diff", a->diff}, {"--json", a->json}});
    // R, G and B, which readImage puts first: an image of other channels (depth, a luminance
    // "Y") is refused by name rather than measured as if it were colour.
    const Image test = readImage(a->test), ref = readImage(a->reference);
    requireRgb(test, a->test, "compare");
    requireRgb(ref, a->reference, "compare");
    const ComparedNames names{a->test, a->reference};
    const ImageErrors e = compareImages(test, ref, a->threshold, names);
    if (!e.placement.empty()) log::warning(e.placement);
    if (e.nonfinitePixels > 0) log::warning(nonfiniteNote(e, names));
    std::printf(
        "rmse      %.6g\nrelmse    %.6g\nmae       %.6g\nmax_abs   %.6g\npsnr      %.3f dB\n"
        "above     %.4f%% of pixels over %.3g\n",
        e.rmse, e.relmse, e.mae, e.maxAbs, e.psnr, 100 * e.aboveThreshold, a->threshold);
    if (!a->diff.empty()) writeDifferenceImage(a->diff, test, ref, names);
    if (!a->json.empty()) writeTextFileAtomically(a->json, errorsJson(e).dump(2) + "\n");
    return kExitOk;
  };
}

}  // namespace glint
