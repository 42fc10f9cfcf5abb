#pragma once
// How a frame is cut into farm tasks and how frames are named (docs/farm.md): a grid of crop
// windows that tile the frame exactly, frame ranges written "A-B", and `####` output names.
// Shared by `glint plan` (what tools/glint-farm submits) and `glint render --frame`.
#include <string>
#include <vector>

#include "film/film.h"

namespace glint {

// `count` crop windows, row-major over a columns × rows grid with columns · rows = count, the
// factorisation whose tiles are closest to square. Tile edges sit at ⌊i·W/columns⌋ and
// ⌊j·H/rows⌋, so the windows cover the frame with no gap and no overlap. Throws UsageError when
// count < 1 or no grid of `count` non-empty tiles fits the frame.
std::vector<PixelWindow> farmTiles(int width, int height, int count, int* columns = nullptr,
                                   int* rows = nullptr);

struct FrameRange {
  int first = 0, last = 0;  // inclusive
  bool contains(int frame) const { return frame >= first && frame <= last; }
  int count() const { return last - first + 1; }
};

// "A-B" or "A" (non-negative integers, A ≤ B); throws UsageError naming `what` otherwise.
FrameRange parseFrameRange(const std::string& text, const std::string& what);

// The path with its last run of '#' in the file name replaced by the frame number, zero-padded
// to the run's length (longer numbers are written in full): "out/a.####.exr", 7 →
// "out/a.0007.exr"; without '#', the name as printf formats it, each "%04d" or "%d" the frame
// (Nuke's and ffmpeg's way) and "%%" a '%'. A path with neither is returned unchanged.
std::string frameFileName(const std::string& pattern, int frame);
bool hasFrameDigits(const std::string& pattern);

}  // namespace glint
