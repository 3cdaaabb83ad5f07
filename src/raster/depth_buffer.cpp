#include "raster/depth_buffer.h"

#include <cmath>

namespace zs {

void DepthBuffer::reset(uint32_t width, uint32_t height, uint32_t layers) {
  width_ = width;
  height_ = height;
  layers_ = layers;
  plane_ = size_t(width) * size_t(height);
  const size_t n = plane_ * size_t(layers);
  depth_.assign(n, INFINITY);  // assign keeps the capacity
  id_.assign(n, kNoId);
}

bool DepthBuffer::insert(size_t p, double z, uint32_t id) {
  z += 0.0;
  if (!(z == z)) return false;  // NaN
  // Is (z, id) nearer than sample l? Equal samples count as not nearer, so a
  // duplicate goes behind its twin (same content either way).
  auto nearer = [&](size_t l) {
    const double d = depth_[l * plane_ + p];
    return z < d || (z == d && id < id_[l * plane_ + p]);
  };
  if (layers_ == 0) return false;
  const size_t last = layers_ - 1;
  const double dl = depth_[last * plane_ + p];
  // Not nearer than the last kept sample (ties by id decide): dropped.
  if (!(z < dl || (z == dl && id < id_[last * plane_ + p]))) return false;
  // Shift the samples behind (z, id) back one layer, from the end.
  size_t l = last;
  while (l > 0 && nearer(l - 1)) {
    depth_[l * plane_ + p] = depth_[(l - 1) * plane_ + p];
    id_[l * plane_ + p] = id_[(l - 1) * plane_ + p];
    --l;
  }
  depth_[l * plane_ + p] = z;
  id_[l * plane_ + p] = id;
  return true;
}

}  // namespace zs
