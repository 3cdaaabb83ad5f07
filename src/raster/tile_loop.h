// The tile loop every renderer runs: tiles handed to threads, finished tiles
// handed to the sink. Each thread takes the next tile in list order, so tiles
// finish nearly row-major, which keeps a streaming sink's out-of-order
// buffers small; a thread that finds the sink busy queues its tile and goes
// on rendering (sink_relay.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "raster/tile_grid.h"
#include "raster/tile_sink.h"

namespace zs {

// Renders one tile on the calling thread and returns its pixels
// (grid.channels floats each, row-major), valid until that thread's next call.
using TileRenderFn = std::function<const float*(uint32_t tile, const TileRect& rect)>;

// Runs `render` for each of `tiles` on `threads` threads (one: in order, on
// the caller's) and delivers every result to `sink`. An exception in any
// tile stops the other threads after their current tile and propagates.
void run_tiles(const TileGrid& grid, const std::vector<uint32_t>& tiles, int threads, TileSink& sink,
               const TileRenderFn& render);

// Every tile id of the grid, in order.
std::vector<uint32_t> all_tiles(const TileGrid& grid);

// How many finished tiles may wait for a busy sink: up to 16 (no more than
// the image has) and at most 64 MiB of them, but at least one (even a tile
// larger than that), none with one thread. Count it against the memory budget.
size_t relay_queue_tiles(const TileGrid& grid, int threads);

}  // namespace zs
