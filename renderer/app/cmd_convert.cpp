// `glint convert IN.exr OUT.png`: develops a rendered EXR into a display image through OCIO,
// without rendering again. Also defines the display options shared with `glint render`.
#include "app/commands.h"
#include "core/log.h"
#include "film/exr_output.h"

namespace glint {

void addDisplayOptions(CLI::App& cmd, DisplaySettings& s) {
  cmd.add_option("--view", s.view, "OCIO view (default: the display's default, Standard)");
  cmd.add_option("--ocio-display", s.display, "OCIO display (default: the config's default, sRGB)");
  cmd.add_option("--look", s.look, "OCIO look(s) applied in scene-linear before the view");
  cmd.add_option("--ocio-config", s.configPath,
                 "OCIO config file (default: $OCIO, else the bundled ocio/config.ocio)");
}

CommandRunner addConvertCommand(CLI::App& app) {
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto settings = std::make_shared<DisplaySettings>();
  CLI::App* cmd =
      app.add_subcommand("convert", "Develop a scene-linear EXR into a display image via OCIO");
  cmd->add_option("input", *in, "Scene-linear EXR (RGBA)")->required()->check(CLI::ExistingFile);
  cmd->add_option("output", *out, "Display image: .png, .jpg or .tif")->required();
  addDisplayOptions(*cmd, *settings);
  return [in, out, settings] {
    const Image img = readImage(*in);
    // One channel is grey, two are grey and alpha, three or more are RGB(A).
    const int nc = img.channels;
    std::vector<float> rgba(size_t(img.width) * size_t(img.height) * 4, 1.0f);
    for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p) {
      const float* src = &img.pixels[p * size_t(nc)];
      float* dst = &rgba[p * 4];
      for (int c = 0; c < 3; ++c) dst[c] = src[nc >= 3 ? c : 0];
      if (nc == 2 || nc >= 4) dst[3] = src[nc == 2 ? 1 : 3];
    }
    // The frame's own colour space, not the config's scene_linear role, which a studio config
    // may set to another space (ACEScg).
    DisplaySettings fromFrame = *settings;
    fromFrame.source = img.colorspace;
    if (img.colorspace.empty())
      log::info(*in + " names no glint:colorspace: taken as the config's scene_linear");
    writeDisplayImage(*out, std::move(rgba), img.width, img.height, fromFrame);
    log::info("wrote " + *out);
    return kExitOk;
  };
}

}  // namespace glint
