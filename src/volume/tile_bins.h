// Faces binned to the screen tiles their pixel-centre boxes touch (once per
// render), in sweep order within each bin: a tile sweeps only its own faces.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/topology.h"
#include "raster/screen_triangle.h"
#include "volume/near_clip.h"
#include "volume/sweep_order.h"

namespace zs {

struct TileBins {
  uint32_t cols = 0, rows = 0;
  std::vector<uint64_t> offset;  // tiles + 1: bin t is items[offset[t], offset[t+1])
  std::vector<uint32_t> items;   // indices into SweepItems, in sweep order
  uint64_t offscreen = 0;        // items that cover no pixel centre of the image
  uint64_t degenerate = 0;       // items with zero screen area (seen edge-on): no fragments
};

// An item's screen triangle.
void item_triangle(const SweepItems& items, size_t k, const Topology& topo, const std::vector<ScreenVertex>& sv,
                   const std::vector<NearTriangle>& near, ScreenVertex out[3]);

// Bins for square tiles of `tile` pixels over a width x height image.
TileBins bin_items(const SweepItems& items, const Topology& topo, const std::vector<ScreenVertex>& sv,
                   const std::vector<NearTriangle>& near, uint32_t width, uint32_t height, uint32_t tile);

// Bytes bin_items needs for `entries` bin entries and `n` items.
inline uint64_t bin_bytes(uint64_t entries, uint64_t n) { return entries * 4 + n * 16; }

// Inclusive pixel-centre range [i0, i1] x [j0, j1] of a triangle inside a
// width x height image; false when it holds no pixel centre.
bool pixel_range(const ScreenVertex v[3], uint32_t width, uint32_t height, int* i0, int* i1, int* j0, int* j1);

}  // namespace zs
