// Deferred segment integration for the exact integrator: the compositor
// queues each segment (which needs nothing of the pixel's state but its ends)
// and a full queue is integrated four at a time (light_kernel.h) and then
// applied to its pixels in queue order — the order the segments were made,
// so every pixel composites exactly as it would one by one. Pieces the
// vector kernel cannot take (a TF breakpoint inside, or the Hermite bound
// failing) go through SegmentIntegrator as before.
#pragma once

#include <cstdint>
#include <vector>

#include "volume/light_kernel.h"
#include "volume/pixel_lists.h"
#include "volume/segment_integrator.h"

namespace zs {

class SegmentBatch {
 public:
  static constexpr size_t kCapacity = 512;  // a multiple of 4
  SegmentBatch(const SegmentIntegrator& integ, const TransferFunction& tf);

  bool full() const { return n_ == kCapacity; }
  void push(uint32_t pixel, double s0, double s1, double len) {
    pixel_[n_] = pixel;
    s0_[n_] = s0;
    s1_[n_] = s1;
    len_[n_] = len;
    ++n_;
  }
  // Integrates the queued segments and composites them into px[pixel].
  void flush(PixelRecord* px);

 private:
  const SegmentIntegrator& integ_;
  const TransferFunction& tf_;
  bool avx2_;
  size_t n_ = 0;
  std::vector<uint32_t> pixel_;
  std::vector<double> s0_, s1_, len_;
  std::vector<double> buf_;  // the kernel's structure of arrays
  std::vector<uint8_t> ok_, split_;
  light::PieceArrays arrays_;
};

}  // namespace zs
