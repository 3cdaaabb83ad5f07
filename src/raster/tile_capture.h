// A sink that keeps the tiles it receives, by tile id, for a second pass over
// the same tiles: a mixed scene's opaque geometry, drawn first, is read back
// by the volume sweep tile by tile (render/volume/opaque_layer.h).
#pragma once

#include <cstdint>
#include <vector>

#include "raster/tile_grid.h"
#include "raster/tile_sink.h"

namespace zs {

class TileCapture : public TileSink {
 public:
  explicit TileCapture(const TileGrid& grid) : grid_(grid), tiles_(grid.count()) {}
  void tile(const TileRect& r, const float* pixels) override {
    const uint32_t t = grid_.tile_of(r);
    tiles_[t].assign(pixels, pixels + grid_.tile_floats(t));
  }
  // The tile's pixels (grid().channels floats each), or null when it was not received.
  const float* pixels(uint32_t tile) const { return tiles_[tile].empty() ? nullptr : tiles_[tile].data(); }
  // Frees the tiles held (their buffers go back to the allocator).
  void clear() {
    for (auto& t : tiles_) std::vector<float>().swap(t);
  }
  const TileGrid& grid() const { return grid_; }

 private:
  TileGrid grid_;
  std::vector<std::vector<float>> tiles_;
};

}  // namespace zs
