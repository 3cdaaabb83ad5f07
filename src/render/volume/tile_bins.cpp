#include "render/volume/tile_bins.h"

#include <algorithm>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "base/util/chunk_offsets.h"

namespace zs {

TileBins bin_items(const SweepItems& items, const Topology& topo, const std::vector<ScreenVertex>& sv,
                   const std::vector<NearTriangle>& near, const ScreenTiling& t, UninitVector<uint32_t> storage) {
  TileBins b;
  b.items = std::move(storage);  // memory already mapped, when given
  b.cols = (t.width + t.tile - 1) / t.tile;
  b.rows = (t.height + t.tile - 1) / t.tile;
  const size_t tiles = size_t(b.cols) * b.rows, n = items.size();
  // Consecutive runs of items (chunks) count their entries per tile, and
  // each chunk's entries of a tile follow the earlier chunks': the bins stay
  // in sweep order however many threads fill them. Boxes over several tiles
  // are recomputed in both passes rather than stored (16 bytes per face).
  size_t chunks = std::clamp<size_t>(n / 65536, 1, 4 * size_t(tbb::this_task_arena::max_concurrency()));
  while (chunks > 1 && chunks * tiles > (size_t(1) << 22)) chunks /= 2;
  std::vector<uint64_t> at(chunks * tiles, 0);
  auto each = [&](size_t c, auto&& visit) {
    const size_t k0 = n * c / chunks, k1 = n * (c + 1) / chunks;
    uint64_t* counts = at.data() + c * tiles;
    for (size_t k = k0; k < k1; ++k) {
      if (items[k].tile != kManyTiles) {
        visit(counts[items[k].tile], uint32_t(k));
        continue;
      }
      ScreenVertex v[3];
      item_triangle(items, k, topo, sv, near, v);
      const TileBox x = item_tile_box(v, t);
      for (uint32_t r = x.r0; r <= x.r1; ++r)
        for (uint32_t col = x.c0; col <= x.c1; ++col) visit(counts[size_t(r) * b.cols + col], uint32_t(k));
    }
  };
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) { each(c, [](uint64_t& count, uint32_t) { ++count; }); });
  b.offset = chunk_offsets(at, chunks, tiles);  // at: where chunk c's entries of each tile start
  b.items.resize(b.offset[tiles]);  // every entry is written below
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) { each(c, [&](uint64_t& pos, uint32_t k) { b.items[pos++] = k; }); });
  return b;
}

}  // namespace zs
