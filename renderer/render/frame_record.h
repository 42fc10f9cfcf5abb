#pragma once
// Everything a frame carries beyond its pixels, written and read in this one place: what
// rendered it (the scene, the settings, the hashes that say which frames may merge or be
// continued), its passes, and the state `glint render --resume` continues from (the channels
// of render/resume_state.h). `glint render` writes it; `render --resume`,
// `converge --from-render` and `merge` read it with readFrameRecord, which refuses an attribute
// that is there but is not what Glint writes (of another type, or malformed), naming the file
// and the attribute. What a frame lacks is each reader's question: merge asks only for
// glint:settings_hash, converge for glint:passes, --resume for its hash and state.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/sampler.h"
#include "core/transform.h"
#include "film/exr_output.h"
#include "film/merge.h"
#include "render/pass_plan.h"
#include "render/render_job.h"
#include "render/resume_state.h"

namespace glint {

class Scene;

// Raised whenever a Glint draws or shades a sample of the same settings differently, so that a
// frame an older one left is refused rather than continued with other samples: 2, progressive
// renders filter textures at the finest footprint (PassPlan::footprintSpp).
inline constexpr uint64_t kSampleRevision = 2;

// What a render was asked for beyond its scene: the command line's choices that the record
// keeps.
struct FrameSettings {
  std::string accel = "embree";
  std::string integrator = "production";
  std::string aovs;  // as --aov gives them
  bool half = false;
  SamplingRequest sampling;
  std::string commandLine;
};

// The attributes of a frame (docs/output.md, The EXR). Each is optional: a frame of an older
// Glint, or a crop another tool wrote, may lack any of them.
struct FrameRecord {
  std::optional<std::string> version;  // glint:version (Software: "Glint " + it)
  std::optional<std::string> scene;    // glint:scene, the scene's path
  // glint:scene_hash (of the scene file's bytes) and glint:settings_hash (crops that merge share
  // it): hex as Glint writes them, compared as text, any text (merge's tests pin crops whose
  // settings hash is "abc" as merged or refused on their pixels, not on the hash).
  std::optional<std::string> sceneHash;
  std::optional<std::string> settingsHash;
  std::optional<std::string> integrator;          // glint:integrator: production or reference
  std::optional<SamplerKind> sampler;             // glint:sampler, the one used
  std::optional<std::vector<PassRecord>> passes;  // glint:passes, the finished ones
  std::optional<uint64_t> resumeHash;             // glint:resume_hash: --resume must match it
  std::optional<std::string> resumeSampling;      // glint:resume_sampling: targets, first pass
  std::optional<std::string> accel;               // glint:accel
  std::optional<uint64_t> seed;                   // glint:seed, as text: 64 bits exact
  std::optional<PixelWindow> crop;                // glint:crop, "x0 x1 y0 y1"
  std::optional<std::string> commandLine;         // glint:commandline
  std::optional<std::string> colorspace;          // glint:colorspace, an OCIO name
  std::optional<int> spp;                         // glint:spp, the scene's (or --spp's)
  // glint:max_spp and glint:time_limit_seconds: where an adaptive or time-limited render's
  // pixels stop, unknown in advance; glint:spp is then only what the scene asked for.
  std::optional<int> maxSpp;
  std::optional<float> timeLimitSeconds;
  std::optional<int> maxDepth;                    // glint:max_depth
  std::optional<bool> partial;                    // glint:partial
  std::optional<int> minPixelSpp, maxPixelSpp;    // glint:min_pixel_spp, glint:max_pixel_spp
  std::optional<int> frame;                       // glint:frame, of an animated scene
  std::optional<float> renderSeconds;             // glint:render_seconds
  std::optional<float> rays;                      // glint:rays
  std::optional<float> estimatedRmse;             // glint:estimated_rmse
  std::optional<float> estimatedRelmse;           // glint:estimated_relmse
  std::optional<Mat4> worldToCamera, worldToNdc;  // worldToCamera, worldToNDC (world space)
  std::optional<float> pixelAspectRatio;          // pixelAspectRatio: a pixel's width / height
  // Written with the frame's pixels, not by writeFrameRecord: by writeExr and merge
  // (glint:clamped_values, glint:merged_crops), by addResumeState (glint:resume_checksum).
  std::optional<int> clampedValues, mergedCrops;
  std::optional<uint64_t> resumeChecksum;
  // Read from the file, not written here: its display window, and whether part 0 holds the
  // resume state's channels.
  int frameWidth = 0, frameHeight = 0;
  bool holdsState = false;
  bool operator==(const FrameRecord&) const;
};

// The record of `result`, a render of `scene` with `settings` by `plan`; `partial` as the frame
// is written (a preview is, the frame it previews may not be).
FrameRecord frameRecord(const Scene& scene, const FrameSettings& settings, const PassPlan& plan,
                        const RenderResult& result, bool partial);

// Adds the record's attributes to `metadata` (Software with glint:version).
void writeFrameRecord(const FrameRecord& record, ExrMetadata& metadata);
// Adds the state --resume continues from to `film` and `metadata` (addResumeState), its
// checksum over the record's resume hash.
void writeResumeState(Film& film, ExrMetadata& metadata, std::span<const PixelEstimate> estimates,
                      const PassPosition& position, const FrameRecord& record);

// The record of `path`'s part 0. Throws UsageError naming the file and the attribute when one is
// of another type than Glint writes or holds what Glint does not write (a hash that is not 16 hex
// digits, a seed that is not a 64-bit whole number, a malformed glint:passes entry, ...).
FrameRecord readFrameRecord(const std::string& path);

// The passes of a record, `key` (glint:passes, or --stats-json's "passes") as JSON text. Throws
// UsageError naming `path` and `key` when it is not JSON or not a list, and the entry and its
// field (`glint:passes[2].spp is -2, not ...`) when an entry is not what a render records: each
// field a render writes, of its type and range; an estimate may be null (one sample, or the
// regular sampler, has none).
std::vector<PassRecord> parsePasses(const std::string& path, const std::string& key,
                                    const std::string& json);
// The same, of a list already parsed (a --stats-json file's "passes").
std::vector<PassRecord> parsePasses(const std::string& path, const std::string& key,
                                    const nlohmann::json& list);
// The passes as the record and --stats-json hold them.
std::string passesJson(const std::vector<PassRecord>& passes);

// What must match for crops of one frame to merge: the scene's bytes and every setting that
// changes pixels. Threads and tile size do not (the image is the same for any of them). `spp`
// stands for the scene's (0 where it must not count), so no caller copies the scene to change it.
uint64_t settingsHash(const Scene& scene, int spp, const std::string& accel,
                      const std::string& extras);

// What must match for --resume to continue a frame: the settings hash without the sample
// counts, the time limit, the AOVs and half floats (they change what is written, not the
// samples; AOVs whose sums are not kept are refused on their own), the sampler actually used,
// for a sampler whose sets are laid out for one total (stratified) that total, and the Glint's
// sample revision.
uint64_t resumeHash(const Scene& scene, const FrameSettings& settings, const PassPlan& plan,
                    uint64_t sampleRevision = kSampleRevision);

// What differs between a frame's record and the one this render writes, as far as the frame's
// tells ("the scene file's bytes; seed: the frame's 1, this render's 9"); empty when nothing it
// records does. `sppLaysOutSets`: the sampler's sets are laid out for the spp, which must match.
std::string resumeDifferences(const FrameRecord& frame, const FrameRecord& render,
                              bool sppLaysOutSets);

struct ResumedFrame {
  ResumeState state;
  std::vector<PassRecord> passes;  // the frame's, as recorded
};

// The state and passes of `path` for a render of `scene` with `settings` by `plan` over
// `window`, after checking it is this frame with these settings. Throws UsageError naming the
// file: no state, a state an older Glint left, another resume hash (naming what the record
// shows to differ, or the sample revision), and what readResumeState refuses.
ResumedFrame readResumable(const std::string& path, const Scene& scene,
                           const FrameSettings& settings, const PassPlan& plan,
                           const PixelWindow& window);

// What merge checks and sums of a crop (film/merge.h), from its record.
CropRecord cropRecord(const std::string& path);

}  // namespace glint
