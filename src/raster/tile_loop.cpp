#include "raster/tile_loop.h"

#include <algorithm>
#include <atomic>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "raster/sink_relay.h"

namespace zs {

std::vector<uint32_t> all_tiles(const TileGrid& grid) {
  std::vector<uint32_t> all(grid.count());
  for (uint32_t t = 0; t < all.size(); ++t) all[t] = t;
  return all;
}

size_t relay_queue_tiles(const TileGrid& grid, int threads) {
  if (threads <= 1) return 0;
  // Tiles as large as they are in this image (clipped), and never more than it has.
  const uint64_t tile_bytes = grid.max_tile_pixels() * grid.channels * 4;
  const uint64_t cap = std::min<uint64_t>(16, grid.count());
  return size_t(std::max<uint64_t>(1, std::min<uint64_t>(cap, (uint64_t(64) << 20) / tile_bytes)));
}

void run_tiles(const TileGrid& grid, const std::vector<uint32_t>& tiles, int threads, TileSink& sink,
               const TileRenderFn& render) {
  threads = std::max(1, threads);
  SinkRelay relay(sink, relay_queue_tiles(grid, threads), grid.channels);
  auto run = [&](size_t k) {
    const uint32_t t = tiles[k];
    const TileRect r = grid.rect(t);
    relay.deliver(r, render(t, r));
  };
  if (threads == 1 || tiles.size() < 2) {
    for (size_t k = 0; k < tiles.size(); ++k) run(k);
  } else {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    std::atomic<size_t> next{0};
    tbb::parallel_for(0, threads, [&](int) {
      for (size_t k = next++; k < tiles.size(); k = next++) {
        try {
          run(k);
        } catch (...) {
          next = tiles.size();  // the others stop after their current tile
          throw;
        }
      }
    });
  }
  relay.finish();
}

}  // namespace zs
