// A sink that assembles the tiles of a render in memory: the RGBA image, and
// for grids with a fifth channel the per-pixel view depth Z (+inf where
// nothing was hit).
#pragma once

#include <algorithm>
#include <vector>

#include "raster/image.h"
#include "raster/tile_sink.h"

namespace zs {

class ImageSink : public TileSink {
 public:
  explicit ImageSink(const TileGrid& grid)
      : channels_(grid.channels), image(grid.width, grid.height) {
    if (channels_ > 4) z.assign(size_t(grid.width) * grid.height, 0.f);
  }
  void tile(const TileRect& r, const float* px) override {
    for (uint32_t y = r.y0; y < r.y1; ++y)
      for (uint32_t x = r.x0; x < r.x1; ++x) {
        const float* p = px + (size_t(y - r.y0) * r.width() + (x - r.x0)) * channels_;
        std::copy(p, p + 4, image.at(x, y));
        if (channels_ > 4) z[size_t(y) * image.width + x] = p[4];
      }
  }

 private:
  uint32_t channels_;

 public:
  Image image;
  std::vector<float> z;  // empty for RGBA-only grids
};

}  // namespace zs
