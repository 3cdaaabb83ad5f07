// The image cut into square screen tiles, the unit every renderer renders,
// every thread or MPI rank takes and every sink receives.
#pragma once

#include <algorithm>
#include <cstdint>

namespace zs {

// Columns [x0, x1), rows [y0, y1) of the image.
struct TileRect {
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  uint32_t width() const { return x1 - x0; }
  uint32_t height() const { return y1 - y0; }
};

// Square tiles of `size` pixels, row-major from the top left; the last
// column and row may be narrower. A finished tile carries `channels` floats
// per pixel: premultiplied R, G, B, A, then (5) the view depth Z of the
// nearest surface, for renderers that have one.
struct TileGrid {
  uint32_t width = 0, height = 0, size = 64;
  uint32_t channels = 4;
  uint32_t cols() const { return (width + size - 1) / size; }
  uint32_t rows() const { return (height + size - 1) / size; }
  uint32_t count() const { return cols() * rows(); }
  TileRect rect(uint32_t tile) const {
    const uint32_t c = tile % cols(), r = tile / cols();
    return {c * size, r * size, std::min(width, (c + 1) * size), std::min(height, (r + 1) * size)};
  }
  // The tile whose rect starts at (r.x0, r.y0).
  uint32_t tile_of(const TileRect& r) const { return (r.y0 / size) * cols() + r.x0 / size; }
  // The most pixels one tile holds: the tile size clipped to the image (a
  // 4096-pixel tile of a 512x512 image is 512x512). Per-tile buffers are
  // sized by their tile's rect, so memory estimates count this, not size².
  uint64_t max_tile_pixels() const { return uint64_t(std::min(size, width)) * std::min(size, height); }
  uint64_t tile_floats(uint32_t tile) const {
    const TileRect r = rect(tile);
    return uint64_t(r.width()) * r.height() * channels;
  }
};

}  // namespace zs
