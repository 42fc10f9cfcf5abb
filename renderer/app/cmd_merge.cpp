// `glint merge OUT.exr CROP.exr...`: assembles crop renders into the full frame.
#include "app/commands.h"
#include "core/log.h"
#include "film/image_format.h"
#include "film/merge.h"
#include "render/frame_record.h"

namespace glint {

CommandRunner addMergeCommand(CLI::App& app) {
  auto out = std::make_shared<std::string>();
  auto crops = std::make_shared<std::vector<std::string>>();
  auto sceneHash = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Assemble crop renders into the full frame (same scene and settings, no holes)");
  cmd->add_option("output", *out, "Merged EXR")->required();
  cmd->add_option("crops", *crops, "Crop EXRs from glint render --crop")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--scene-hash", *sceneHash,
                  "Refuse crops whose glint:scene_hash differs (a farm passes the planned hash)")
      ->check(nonEmpty());
  return [out, crops, sceneHash] {
    imageOutputFormat("merge's output", *out, ImageOutput::Exr);
    std::vector<CropRecord> records;
    for (const std::string& crop : *crops) records.push_back(cropRecord(crop));
    const MergeReport r = mergeCrops(*out, records, commandLine(), *sceneHash);
    log::info("merged " + std::to_string(r.crops) + " crops into " + *out + " (" +
              std::to_string(r.fullWidth) + "x" + std::to_string(r.fullHeight) + ")");
    return kExitOk;
  };
}

}  // namespace glint
