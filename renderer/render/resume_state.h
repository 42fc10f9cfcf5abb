#pragma once
// What `glint render --resume` continues from: each pixel's state between passes
// (render/pixel_estimate.h) and where the frame's passes stood, stored with the frame as the
// UINT channels glint_resume.00 to .22 (per half: mean R, G, B and coverage as each double's 64
// bits in two channels, high word first, then the sample count, then the rays traced in two
// channels; last, whether the pass a stop cut short had chosen the pixel) and the attributes
// glint:resume_finished_end, glint:resume_cut_end and glint:resume_checksum. Bits, not values:
// a resumed render adds its samples to exactly the state a straight one would have, and takes
// the same choices, so it writes the same pixels.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "film/exr_output.h"
#include "film/film.h"
#include "render/pixel_estimate.h"

namespace glint {

inline constexpr const char* kResumeLayer = "glint_resume";
// The attributes that place the state: where its passes stood, and its checksum.
inline constexpr const char* kResumeFinishedEndKey = "glint:resume_finished_end";
inline constexpr const char* kResumeCutEndKey = "glint:resume_cut_end";
inline constexpr const char* kResumeChecksumKey = "glint:resume_checksum";

// Where a frame's passes stood when it was written. Adaptive choices read the state the
// previous pass left; a pass cut short (a signal, the time limit) has moved some of its pixels
// and not others, so its choice cannot be taken again from the state: it is kept.
struct PassPosition {
  int finishedEnd = 0;             // the end of the last pass finished; 0: none
  int cutEnd = 0;                  // the end of the pass a stop cut short; 0: none
  std::vector<uint8_t> cutChosen;  // the pixels that pass had chosen (the window's, row-major)
  bool operator==(const PassPosition&) const = default;
};

struct ResumeState {
  PixelEstimates estimates;  // the window's pixels, row-major
  PassPosition position;
};

// The bytes a pixel's state adds to a frame written with it: its channels in the film's plane
// and packed for the file, and the copy of the pixel's RGBA the frame written with them is.
size_t resumeStateBytesPerPixel();

// Adds the state plane to `film` (whose window the estimates cover, row-major) and the
// position's attributes to `metadata`, with a checksum over both and `resumeHash`.
void addResumeState(Film& film, ExrMetadata& metadata, std::span<const PixelEstimate> estimates,
                    const PassPosition& position, const std::string& resumeHash);

// The state of `path`'s part 0, which must cover exactly `window` of a full frame of
// fullWidth × fullHeight. Throws UsageError naming the file when the state is missing, of
// another shape, or holds what no render leaves (a non-finite value, a negative coverage, a
// count past `maxSamples`, fewer rays than samples or more than 2^62, a pixel past the passes
// the position names); and, given the frame's `resumeHash`, when its glint:resume_checksum is
// not that of the state and the hash: the state was altered (a tool that converted its words to
// float, an edit) or taken from another frame.
ResumeState readResumeState(const std::string& path, const PixelWindow& window, int fullWidth,
                            int fullHeight, int64_t maxSamples,
                            const std::string* resumeHash = nullptr);

}  // namespace glint
