// `glint plan SCENE --tiles N [--frames A-B]`: what a render farm should run for a scene
// (docs/farm.md). It prints, one fact per line, the frame size and spp after overrides, the frames,
// the scene hash a finished frame must carry, and the crop of every tile; tools/glint-farm reads
// it, and any other farm manager can.
#include <cstdio>

#include "app/commands.h"
#include "app/farm_plan.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "core/sampler.h"
#include "film/image_format.h"

namespace glint {

namespace {

struct PlanArgs {
  std::string scenePath;
  int tiles = 1;
  std::string frames;
  std::string output;
  std::optional<int> width, height, spp;
};

int runPlan(const PlanArgs& a) {
  // A farm's frame is merged from its tiles, and merge writes EXR.
  if (!a.output.empty()) imageOutputFormat("-o", a.output, ImageOutput::Exr);
  Scene scene = loadSceneOrDefault(a.scenePath);
  if (a.width) scene.render.width = *a.width;
  if (a.height) scene.render.height = *a.height;
  if (a.spp) scene.render.spp = *a.spp;
  std::optional<FrameRange> frames;
  if (scene.animation) frames = FrameRange{scene.animation->first, scene.animation->last};
  if (!a.frames.empty()) {
    const FrameRange asked = parseFrameRange(a.frames, "--frames");
    if (!frames)
      throw UsageError("--frames " + a.frames +
                       ": the scene is not animated (it declares no \"animation\")");
    if (!frames->contains(asked.first) || !frames->contains(asked.last))
      throw UsageError("--frames " + a.frames + " lies outside the scene's frames " +
                       std::to_string(frames->first) + "-" + std::to_string(frames->last));
    frames = asked;
  }
  if (frames && frames->count() > 1 && !a.output.empty() && !hasFrameDigits(a.output))
    throw UsageError("-o " + a.output + ": " + std::to_string(frames->count()) +
                     " frames need a run of # in the file name for the frame number "
                     "(name.####.exr)");
  int columns = 0, rows = 0;
  const auto tiles = farmTiles(scene.render.width, scene.render.height, a.tiles, &columns, &rows);

  std::printf("scene %s\n", scene.sourcePath.c_str());
  std::printf("scene_hash %016llx\n", static_cast<unsigned long long>(scene.sourceHash));
  std::printf("size %d %d\n", scene.render.width, scene.render.height);
  std::printf("spp %d\n", scene.render.spp);
  if (frames)
    std::printf("frames %d %d\n", frames->first, frames->last);
  else
    std::printf("frames none\n");
  std::printf("grid %d %d\n", columns, rows);
  if (!a.output.empty()) {
    if (!frames)
      std::printf("output - %s\n", a.output.c_str());
    else
      for (int f = frames->first; f <= frames->last; ++f)
        std::printf("output %d %s\n", f, frameFileName(a.output, f).c_str());
  }
  for (size_t k = 0; k < tiles.size(); ++k)
    std::printf("tile %zu %d %d %d %d\n", k, tiles[k].x0, tiles[k].x1, tiles[k].y0, tiles[k].y1);
  return kExitOk;
}

}  // namespace

CommandRunner addPlanCommand(CLI::App& app) {
  auto args = std::make_shared<PlanArgs>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "Print the tiles and frames a render farm runs for a scene (docs/farm.md)");
  cmd->add_option("scene", args->scenePath, sceneArgumentHelp())->check(CLI::ExistingFile);
  cmd->add_option("--tiles", args->tiles, "Tiles per frame (a grid of near-square crops)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--frames", args->frames,
                  "Frames A-B (or A) of an animated scene (default: all it declares)")
      ->check(nonEmpty());
  cmd->add_option("-o,--output", args->output,
                  "Output EXR; with frames, name.####.exr: prints each frame's file name");
  cmd->add_option("--width", args->width, "Image width")->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--height", args->height, "Image height")->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--spp", args->spp, "Samples per pixel")
      ->check(CLI::Range(1, static_cast<int>(kMaxSampleSet)));
  return [args] { return runPlan(*args); };
}

}  // namespace glint
