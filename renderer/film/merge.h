#pragma once
// Assembles crop renders (`glint render --crop`) into the full frame. Crops must come from the
// same scene and settings (glint:settings_hash), have the same channels (beauty and layered
// AOVs) in the same types, be complete (not interrupted), and tile the frame without overlaps
// or holes; the result's pixels are the crops' bytes.
#include <optional>
#include <string>
#include <vector>

#include "film/film.h"

namespace glint {

struct MergeReport {
  int fullWidth = 0, fullHeight = 0;
  size_t crops = 0;
};

// What merge checks and sums of a crop's record, read from its file by
// render/frame_record.h's cropRecord (absent attributes as empty, false and 0).
struct CropRecord {
  std::string path;
  std::string settingsHash;  // glint:settings_hash, hex; empty: none
  std::string sceneHash;     // glint:scene_hash, hex; empty: none
  bool partial = false;      // glint:partial
  float renderSeconds = 0;   // glint:render_seconds
  float rays = 0;            // glint:rays
  int clampedValues = 0;     // glint:clamped_values
  // glint:estimated_rmse and glint:estimated_relmse, glint:min_pixel_spp and
  // glint:max_pixel_spp: what the merged frame's own are made of.
  std::optional<float> estimatedRmse, estimatedRelmse;
  std::optional<int> minPixelSpp, maxPixelSpp;
};

// Throws UsageError naming the offending files, the overlapping pixel, or the missing regions
// as `--crop X0 X1 Y0 Y1` lines that re-render exactly them.
// `commandLine` is recorded as the merged file's glint:commandline. A non-empty
// `expectedSceneHash` (hex, as in glint:scene_hash) refuses crops of any other scene file: a farm
// passes the hash it planned with, so a scene edited while the job ran is caught.
MergeReport mergeCrops(const std::string& outPath, const std::vector<CropRecord>& crops,
                       const std::string& commandLine, const std::string& expectedSceneHash = {});

// Missing pixels of a coverage mask (row-major, width × height, true = covered) as disjoint
// rectangles, greedily: each starts at the first missing pixel in row order, runs right while
// pixels are missing and grows down while the whole run is missing.
std::vector<PixelWindow> missingRegions(const std::vector<bool>& covered, int width, int height);
// The same rectangles for a frame covered by `crops` (inside the frame, not overlapping),
// found on the grid their edges cut, so the cost follows the number of crops, not of pixels.
std::vector<PixelWindow> missingRegions(const std::vector<PixelWindow>& crops, int width,
                                        int height);

}  // namespace glint
