// Screen triangles binned to the tiles their pixel-centre boxes touch, as
// compressed rows (offsets, ids): the per-tile work list of the z-buffer
// renderers (the surface renderer, the shadow-map builder). Within a tile the
// ids keep their input order.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/screen_triangle.h"
#include "raster/tile_grid.h"

namespace zs {

struct TriangleBins {
  std::vector<uint64_t> offsets;  // grid.count() + 1
  std::vector<uint32_t> ids;      // triangle indices, tile by tile
  const uint32_t* begin(uint32_t tile) const { return ids.data() + offsets[tile]; }
  const uint32_t* end(uint32_t tile) const { return ids.data() + offsets[tile + 1]; }
  uint64_t entries() const { return ids.size(); }
};

// Bins triangles (corner indices into `verts`) by the box of their corners'
// pixel coordinates, widened to the pixel centres it may contain. Triangles
// whose box holds no pixel centre of the image are not binned.
void bin_triangles(const TileGrid& grid, const std::vector<ScreenVertex>& verts,
                   const std::vector<std::array<uint32_t, 3>>& corners, TriangleBins* out);

}  // namespace zs
