// Items binned to the screen tiles their pixel-centre boxes touch (once per
// render), in sweep order within each bin: a tile sweeps only its own faces.
#pragma once

#include <cstdint>
#include <vector>

#include "render/volume/sweep_order.h"

namespace zs {

struct TileBins {
  uint32_t cols = 0, rows = 0;
  std::vector<uint64_t> offset;  // tiles + 1: bin t is items[offset[t], offset[t+1])
  UninitVector<uint32_t> items;  // indices into SweepItems, in sweep order
};

// Bins for the tiling the items were made with (sweep_order), on the calling
// thread's TBB arena; the bins do not depend on its thread count.
TileBins bin_items(const SweepItems& items, const Topology& topo, const std::vector<ScreenVertex>& sv,
                   const std::vector<NearTriangle>& near, const ScreenTiling& tiling,
                   UninitVector<uint32_t> storage = {});

}  // namespace zs
