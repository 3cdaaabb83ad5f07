// The frame's bins: each visible sphere listed under every screen tile its
// silhouette box touches, nearest first (the opaque renderer's front-to-back
// order, spheres digest §2.2.5), so a tile's early depth test (the sphere's
// nearest possible depth against the buffer) skips most hidden spheres.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/tile_grid.h"
#include "render/spheres/sphere_grid.h"
#include "base/util/memory_ledger.h"
#include "base/view/camera.h"

namespace zs {

struct SphereBins {
  std::vector<uint64_t> offset;  // tiles + 1: tile t lists ids[offset[t], offset[t + 1])
  std::vector<uint32_t> ids;     // grid entries, nearest first in each tile
};

// Bins the grid entries `visible`; the ledger holds what the bins take, and
// throws before they are filled when the budget cannot hold them.
SphereBins bin_spheres(const SphereGrid& g, const std::vector<uint32_t>& visible, const View& view,
                       const TileGrid& grid, int threads, MemoryLedger& ledger);

}  // namespace zs
