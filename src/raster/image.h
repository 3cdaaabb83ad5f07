// A float RGBA image, premultiplied, linear; row 0 at the top. What a render
// held in memory produces (output/image_io.h reads and writes them).
#pragma once

#include <cstdint>
#include <vector>

namespace zs {

struct Image {
  uint32_t width = 0, height = 0;
  std::vector<float> rgba;  // 4 floats per pixel
  Image() = default;
  Image(uint32_t w, uint32_t h) : width(w), height(h), rgba(size_t(w) * h * 4, 0.f) {}
  float* at(uint32_t x, uint32_t y) { return &rgba[(size_t(y) * width + x) * 4]; }
  const float* at(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

}  // namespace zs
