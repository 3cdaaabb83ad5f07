// A sink that assembles the tiles of a render in memory: the RGBA image, for
// grids with a fifth channel the per-pixel view depth Z (+inf where nothing
// was hit), and any channels after it (the surface renderer's lit0, ...).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "raster/image.h"
#include "raster/tile_sink.h"

namespace zs {

class ImageSink : public TileSink {
 public:
  explicit ImageSink(const TileGrid& grid)
      : channels_(grid.channels), image(grid.width, grid.height) {
    if (channels_ > 4) z.assign(size_t(grid.width) * grid.height, 0.f);
    if (channels_ > 5) extra.assign(size_t(grid.width) * grid.height * (channels_ - 5), 0.f);
  }
  void tile(const TileRect& r, const float* px) override {
    for (uint32_t y = r.y0; y < r.y1; ++y)
      for (uint32_t x = r.x0; x < r.x1; ++x) {
        const float* p = px + (size_t(y - r.y0) * r.width() + (x - r.x0)) * channels_;
        std::copy(p, p + 4, image.at(x, y));
        if (channels_ > 4) z[size_t(y) * image.width + x] = p[4];
        if (channels_ > 5)
          std::copy(p + 5, p + channels_, extra.begin() + std::ptrdiff_t((size_t(y) * image.width + x) * (channels_ - 5)));
      }
  }

 private:
  uint32_t channels_;

 public:
  Image image;
  std::vector<float> z;  // empty for RGBA-only grids
  std::vector<float> extra;  // channels 5.. per pixel, pixel-major
  // Channel 5 + c of pixel (x, y).
  float channel(uint32_t x, uint32_t y, uint32_t c) const {
    return extra[(size_t(y) * image.width + x) * (channels_ - 5) + c];
  }
};

}  // namespace zs
