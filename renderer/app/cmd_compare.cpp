// `glint compare A.exr B.exr`: error metrics of A against the reference B.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "film/atomic_file.h"
#include "film/compare.h"

namespace glint {

nlohmann::json errorsJson(const ImageErrors& e) {
  const auto finite = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  return {{"rmse", finite(e.rmse)}, {"relmse", finite(e.relmse)},
          {"mae", finite(e.mae)},   {"max_abs", finite(e.maxAbs)},
          {"psnr", finite(e.psnr)}, {"share_above_threshold", e.aboveThreshold},
          {"pixels", e.pixels}};
}

namespace {

// Compare measures R, G and B, which readImage puts first (with or without a layer prefix,
// "beauty.R"); an image of other channels (depth, a luminance "Y") is refused by name rather
// than measured as if it were colour.
void requireRgb(const Image& img, const std::string& path) {
  const auto is = [&](int c, char name) {
    if (c >= int(img.channelNames.size())) return false;
    const std::string& n = img.channelNames[size_t(c)];
    return n.size() >= 1 && n.back() == name && (n.size() == 1 || n[n.size() - 2] == '.');
  };
  if (is(0, 'R') && is(1, 'G') && is(2, 'B')) return;
  std::string names;
  for (const std::string& n : img.channelNames) names += (names.empty() ? "" : ", ") + n;
  throw UsageError(path + ": compare needs R, G and B channels; it has " +
                   excerpt(names.empty() ? "none" : names));
}

}  // namespace

CommandRunner addCompareCommand(CLI::App& app) {
  struct Args {
    std::string test, reference, diff, json;
    double threshold = 1e-2;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("compare", "Error metrics between an image and a reference");
  cmd->add_option("image", a->test, "Image to measure (EXR)")->required()->check(CLI::ExistingFile);
  cmd->add_option("reference", a->reference, "Reference image (EXR)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--threshold", a->threshold,
                  "Per-pixel error counted in share_above_threshold (default 0.01)")
      ->check(positiveNumber());
  cmd->add_option("--diff", a->diff, "Write a false-colour difference image (PNG)");
  cmd->add_option("--json", a->json, "Write the figures as JSON");
  return [a] {
    const Image test = readImage(a->test), ref = readImage(a->reference);
    requireRgb(test, a->test);
    requireRgb(ref, a->reference);
    const ImageErrors e = compareImages(test, ref, a->threshold);
    std::printf(
        "rmse      %.6g\nrelmse    %.6g\nmae       %.6g\nmax_abs   %.6g\npsnr      %.3f dB\n"
        "above     %.4f%% of pixels over %.3g\n",
        e.rmse, e.relmse, e.mae, e.maxAbs, e.psnr, 100 * e.aboveThreshold, a->threshold);
    if (!a->diff.empty()) writeDifferenceImage(a->diff, test, ref);
    if (!a->json.empty()) writeTextFileAtomically(a->json, errorsJson(e).dump(2) + "\n");
    return kExitOk;
  };
}

}  // namespace glint
