#pragma once
// Where a render's time goes around its parallel phases (`glint render --stats-json`'s
// "schedule"; tools/project-scaling.py projects from it how the render scales with cores,
// docs/performance.md, Scaling with cores): the work one thread does while the others wait,
// and how each pass's tiles shared out the threads.
#include <vector>

#include "render/tile_scheduler.h"

namespace glint {

// One phase of tiles: a pass, or the probes that measure adaptive sampling's spread.
struct PassTiming {
  int spp = 0;  // the pass's end; 0 for the probes
  // Since the phase before ended: in loops over the frame's pixels on the render's threads
  // (choices, tile costs, statistics), and the rest, on the driving thread alone.
  double loopSeconds = 0, serialSeconds = 0;
  double tilesSeconds = 0;      // from the phase's start to its last tile's end
  std::vector<TileTime> tiles;  // in the order taken
};

struct RenderTiming {
  int threads = 0;
  int width = 0, height = 0;  // of the pixels sampled (the frame, or the crop and its apron)
  int tileSize = 0;           // the effective tile edge (effectiveTileSize)
  double setupSeconds = 0;    // the session's construction on one thread, its buffers unwritten
  double initSeconds = 0;     // the buffers' first writes, on the render's threads
  std::vector<PassTiming> passes;
  // After the last phase: the frame resolved and its statistics, in loops over its pixels,
  // and the rest.
  double finishLoopSeconds = 0, finishSeconds = 0;
};

}  // namespace glint
