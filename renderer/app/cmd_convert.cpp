// `glint convert IN.exr OUT.png`: develops a rendered EXR into a display image through OCIO,
// without rendering again. Also defines the display options shared with `glint render`.
#include "app/commands.h"
#include "core/log.h"
#include "film/exr_output.h"
#include "film/image_format.h"
#include "film/input_colorspace.h"
#include "film/rgb_channels.h"

namespace glint {

void addDisplayOptions(CLI::App& cmd, DisplaySettings& s) {
  cmd.add_option("--view", s.view,
                 std::string("OCIO view (default: the display's default; the bundled config's is "
                             "\"") +
                     kBundledDefaultView + "\")");
  cmd.add_option("--ocio-display", s.display,
                 std::string("OCIO display (default: the config's default; the bundled config's "
                             "is \"") +
                     kBundledDefaultDisplay + "\")");
  cmd.add_option("--look", s.look, "OCIO look(s) applied in scene-linear before the view");
  cmd.add_option("--ocio-config", s.configPath,
                 "OCIO config file (default: $OCIO, else the bundled ocio/config.ocio)");
}

namespace {

// --input-colorspace must name a colour space of the active config.
void checkInputColorspace(const std::string& name, const std::string& configPath) {
  if (name.empty() || ocioHasColorSpace(configPath, name)) return;
  std::string names;
  for (const std::string& n : ocioColorSpaces(configPath)) names += (names.empty() ? "" : ", ") + n;
  throw UsageError("--input-colorspace " + inQuotes(name) +
                   " is not a colour space of the OCIO config; it has: " + names);
}

int runConvert(const std::string& in, const std::string& out, const DisplaySettings& settings,
               const std::string& named) {
  imageOutputFormat("convert's output", out, ImageOutput::Display);
  checkInputColorspace(named, settings.configPath);
  const Image img = readImage(in);
  requireRgb(img, in, "convert");
  const bool alpha = hasAlpha(img);
  const size_t nc = size_t(img.channels), pixels = size_t(img.width) * size_t(img.height);
  std::vector<float> rgba(pixels * 4, 1.0f);
  // Transparent when some pixel's alpha is below 1: then PNG and TIFF keep the alpha.
  bool transparent = false;
  for (size_t p = 0; p < pixels; ++p) {
    const float* src = &img.pixels[p * nc];
    float* dst = &rgba[p * 4];
    for (int c = 0; c < 3; ++c) dst[c] = src[c];
    if (alpha) dst[3] = src[3];
    transparent |= dst[3] < 1;
  }
  // The frame's own colour space, not the config's scene_linear role, which a studio config
  // may set to another space (ACEScg).
  const InputColorspace space = inputColorspace(img, in, named);
  DisplaySettings fromFrame = settings;
  fromFrame.source = space.source;
  fromFrame.toSource = space.toSource;
  log::info(in + " is taken as " + space.why);
  writeDisplayImage(out, std::move(rgba), img.width, img.height, fromFrame, transparent);
  log::info("wrote " + out);
  return kExitOk;
}

}  // namespace

CommandRunner addConvertCommand(CLI::App& app) {
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto named = std::make_shared<std::string>();
  auto settings = std::make_shared<DisplaySettings>();
  CLI::App* cmd =
      app.add_subcommand("convert", "Develop a scene-linear EXR into a display image via OCIO");
  cmd->add_option("input", *in, "Scene-linear EXR (R, G, B, optional A)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("output", *out, "Display image: .png, .jpg or .tif")->required();
  cmd->add_option("--input-colorspace", *named,
                  "The input's OCIO colour space (default: its glint:colorspace, else the space "
                  "its chromaticities define, else the config's scene_linear)");
  addDisplayOptions(*cmd, *settings);
  return [in, out, settings, named] { return runConvert(*in, *out, *settings, *named); };
}

}  // namespace glint
