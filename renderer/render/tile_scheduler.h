#pragma once
// Splits a pixel window into square tiles and runs them on TBB inside a task_arena capped at
// the requested thread count. Each tile is rendered by one task; results are reduced in tile
// order, so the output never depends on threads or scheduling.
#include <functional>
#include <vector>

#include "film/film.h"

namespace glint {

std::vector<PixelWindow> makeTiles(const PixelWindow& window, int tileSize);

// Runs renderTile(tileIndex) for every tile on `threads` threads (0 = all cores).
void runTiles(const std::vector<PixelWindow>& tiles, int threads,
              const std::function<void(size_t tileIndex)>& renderTile);

int defaultThreadCount();

}  // namespace glint
