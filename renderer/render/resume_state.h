#pragma once
// What `glint render --resume` continues from: each pixel's state between passes
// (render/pixel_estimate.h), stored with the frame as the UINT channels glint_resume.00 to .21
// (per half: mean R, G, B and coverage as each double's 64 bits in two channels, high word
// first, then the sample count, then the rays traced in two channels). Bits, not values: a
// resumed render adds its samples to exactly the state a straight one would have, so it writes
// the same pixels.
#include <string>
#include <vector>

#include "film/film.h"
#include "render/pixel_estimate.h"

namespace glint {

inline constexpr const char* kResumeLayer = "glint_resume";

// Adds the state plane to `film` (whose window the estimates cover, row-major).
void addResumeState(Film& film, const std::vector<PixelEstimate>& estimates);

// The state of `path`'s part 0, which must cover exactly `window` of a full frame of
// fullWidth × fullHeight. Throws UsageError naming the file when the state is missing, of
// another shape, or holds what no render leaves (a non-finite value, a negative coverage, a
// count past `maxSamples`, fewer rays than samples or more than 2^62).
std::vector<PixelEstimate> readResumeState(const std::string& path, const PixelWindow& window,
                                           int fullWidth, int fullHeight, int64_t maxSamples);

}  // namespace glint
