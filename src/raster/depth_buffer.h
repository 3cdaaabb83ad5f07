// A depth buffer keeping, per pixel, the k nearest (depth, id) samples.
//
// Samples are ordered by (depth, id): at equal depth the smaller id is in
// front. That is a total order, so the buffer's content is a function of
// the set of samples written, never of their arrival order: tiles, threads
// and culling give bit-identical images. −0.0 is stored as +0.0 (they compare
// equal, and bits must not depend on which came first); NaN depths are
// never written.
//
// Layer-major storage (layer l of pixel p at l·width·height + p): with k = 1
// it is two plain row-major arrays, and layer 0 stays contiguous for any k
// (depths()); k > 1 pays a stride per layer, and k is small.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zs {

constexpr uint32_t kNoId = 0xffffffffu;

class DepthBuffer {
 public:
  // Every sample (+inf, kNoId); reuses memory.
  void reset(uint32_t width, uint32_t height, uint32_t layers = 1);
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t layers() const { return layers_; }

  // k = 1: keeps the nearer of (z, id) and the stored sample; true when
  // (z, id) is now the front sample (also when it equals the stored one).
  bool test_write(size_t p, double z, uint32_t id) {
    z += 0.0;  // −0 → +0
    double& d = depth_[p];
    uint32_t& i = id_[p];
    if (z < d || (z == d && id <= i)) {
      d = z;
      i = id;
      return true;
    }
    return false;
  }

  // Any k: inserts (z, id) into pixel p's sorted samples if it is nearer than
  // the last one (equal samples are kept side by side); true when inserted.
  bool insert(size_t p, double z, uint32_t id);

  // Only tests: would (z, id) be in front of the front sample?
  bool passes(size_t p, double z, uint32_t id) const {
    z += 0.0;
    return z < depth_[p] || (z == depth_[p] && id < id_[p]);
  }

  double depth(size_t p, uint32_t layer = 0) const { return depth_[size_t(layer) * plane_ + p]; }
  uint32_t id(size_t p, uint32_t layer = 0) const { return id_[size_t(layer) * plane_ + p]; }
  const double* depths() const { return depth_.data(); }  // layer 0, row-major (width·height)
  // Layer 0's depths and ids for loops that test a whole row (k = 1; the
  // same rule as test_write).
  double* front_depths() { return depth_.data(); }
  uint32_t* front_ids() { return id_.data(); }

 private:
  uint32_t width_ = 0, height_ = 0, layers_ = 0;
  size_t plane_ = 0;  // width·height
  std::vector<double> depth_;
  std::vector<uint32_t> id_;
};

}  // namespace zs
