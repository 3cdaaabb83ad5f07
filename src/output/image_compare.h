// Image differences for accuracy work: max abs, RMSE, PSNR (peak 1), and
// the number of pixels whose largest channel difference exceeds 1/255.
#pragma once

#include <cstdint>

#include "output/image_io.h"

namespace zs {

struct ImageDiff {
  double max_abs = 0, rmse = 0, psnr = 0;  // psnr = +inf for identical images
  uint64_t pixels_over_1_255 = 0;
  uint32_t worst_x = 0, worst_y = 0;
};

// Throws std::invalid_argument when the sizes differ. channels: 4 compares
// RGBA, 3 only RGB (for an image without alpha, such as a screen grab over
// black, against a premultiplied render).
ImageDiff compare_images(const Image& a, const Image& b, int channels = 4);
// False colour: black = equal, through blue and green to red at `scale`
// (per-pixel max difference over the first `channels`); opaque.
Image difference_image(const Image& a, const Image& b, double scale, int channels = 4);

}  // namespace zs
