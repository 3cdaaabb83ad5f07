#include "output/image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace zs {

ImageDiff compare_images(const Image& a, const Image& b, int channels) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
  if (channels != 3 && channels != 4) throw std::invalid_argument("channels must be 3 or 4");
  ImageDiff d;
  double sum2 = 0;
  const size_t n = size_t(a.width) * a.height;
  for (size_t p = 0; p < n; ++p) {
    double worst = 0;
    for (int c = 0; c < channels; ++c) {
      const double e = std::abs(double(a.rgba[p * 4 + c]) - double(b.rgba[p * 4 + c]));
      sum2 += e * e;
      worst = std::max(worst, std::isnan(e) ? INFINITY : e);
    }
    if (worst > 1.0 / 255.0) ++d.pixels_over_1_255;
    if (worst > d.max_abs) {
      d.max_abs = worst;
      d.worst_x = uint32_t(p % a.width);
      d.worst_y = uint32_t(p / a.width);
    }
  }
  d.rmse = n ? std::sqrt(sum2 / double(size_t(channels) * n)) : 0.0;
  d.psnr = d.rmse > 0 ? 20.0 * std::log10(1.0 / d.rmse) : std::numeric_limits<double>::infinity();
  return d;
}

Image difference_image(const Image& a, const Image& b, double scale, int channels) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("images differ in size");
  if (channels != 3 && channels != 4) throw std::invalid_argument("channels must be 3 or 4");
  Image out(a.width, a.height);
  for (size_t p = 0; p < size_t(a.width) * a.height; ++p) {
    double worst = 0;
    for (int c = 0; c < channels; ++c) worst = std::max(worst, std::abs(double(a.rgba[p * 4 + c]) - double(b.rgba[p * 4 + c])));
    const double t = std::isnan(worst) ? 1.0 : std::clamp(worst / scale, 0.0, 1.0);
    // 0 -> black, 1/3 -> blue, 2/3 -> green, 1 -> red.
    float r = 0, g = 0, bl = 0;
    if (t > 0) {
      if (t < 1.0 / 3) bl = float(3 * t);
      else if (t < 2.0 / 3) bl = float(2 - 3 * t), g = float(3 * t - 1);
      else g = float(3 - 3 * t), r = float(3 * t - 2);
    }
    float* o = &out.rgba[p * 4];
    o[0] = r, o[1] = g, o[2] = bl, o[3] = 1.f;
  }
  return out;
}

}  // namespace zs
