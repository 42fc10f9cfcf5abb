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
    std::vector<float> rgba(size_t(img.width) * size_t(img.height) * 4, 1.0f);
    for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p)
      for (int c = 0; c < std::min(img.channels, 4); ++c)
        rgba[p * 4 + size_t(c)] = img.pixels[p * size_t(img.channels) + size_t(c)];
    writeDisplayImage(*out, std::move(rgba), img.width, img.height, *settings);
    log::info("wrote " + *out);
    return kExitOk;
  };
}

}  // namespace glint
