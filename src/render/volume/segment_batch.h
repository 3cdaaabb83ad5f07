// Deferred segment integration for the exact integrator: the compositor
// queues each segment (which needs nothing of the pixel's state but its ends)
// and a full queue is integrated by the widest vector kernel the CPU has
// (light_kernel.h: transfer-function lookups and the piece's light, 8 or 4
// segments at a time) and then applied to its pixels in queue order — the
// order the segments were made, so every pixel composites exactly as it
// would one by one. Segments the one-piece kernel cannot take (a TF
// breakpoint inside, or the Hermite bound failing on a thick piece) are
// retried by the kernel in pieces; the few left go through SegmentIntegrator.
#pragma once

#include <cstdint>
#include <vector>

#include "base/optics/light_kernel.h"
#include "render/volume/pixel_lists.h"
#include "base/optics/segment_integrator.h"

namespace zs {

// Which kernel a batch runs: the widest the CPU supports unless capped
// (tests compare them; ZSWEEP_KERNEL=scalar|avx2|avx512 caps it too).
enum class KernelWidth { Scalar = 1, AVX2 = 4, AVX512 = 8 };
KernelWidth best_kernel_width();
// Double (the default; every width gives the same bits) or single precision
// (light_kernel.h's Lane1f / Lane8f: AVX2 or scalar, the same bits).
enum class KernelPrecision { Double, Single };
// The kernel a batch with these settings runs on this CPU: "avx512", "avx2",
// "scalar", "avx2-f32" or "scalar-f32" (the stats name it).
const char* kernel_name(KernelWidth width, KernelPrecision precision);

class SegmentBatch {
 public:
  static constexpr size_t kCapacity = 512;  // a multiple of 16
  static constexpr int kSplitParts = 2;     // retried segments: 2 halves x 2 pieces
  SegmentBatch(const SegmentIntegrator& integ, const TransferFunction& tf, KernelWidth width = best_kernel_width(),
               KernelPrecision precision = KernelPrecision::Double);

  bool full() const { return n_ == kCapacity; }
  void push(uint32_t pixel, double s0, double s1, double len) {
    pixel_[n_] = pixel;
    s0_[n_] = s0;
    s1_[n_] = s1;
    len_[n_] = len;
    ++n_;
  }
  // Integrates the queued segments and composites them into light[pixel].
  void flush(PixelLight* light);
  // The same segments' light without compositing (tests): rgb and T per segment.
  void integrate(std::vector<SegmentLight>* out);

 private:
  void run_kernel();
  void run_pass(double* s0, double* s1, double* len, size_t n, double* r, double* g, double* b, double* T,
                uint8_t* ok, int parts);

  const SegmentIntegrator& integ_;
  const TransferFunction& tf_;
  KernelWidth width_;
  KernelPrecision precision_;
  size_t n_ = 0;
  std::vector<uint32_t> pixel_;
  std::vector<double> s0_, s1_, len_, n0_, n1_, rgb_[3], T_;
  std::vector<uint8_t> ok_;
  // The second pass (segments in pieces): their indices and arrays.
  std::vector<uint32_t> retry_;
  std::vector<double> r_s0_, r_s1_, r_len_, r_rgb_[3], r_T_;
  std::vector<uint8_t> r_ok_;
  std::vector<double> tables_;  // TfTables' storage
  light::TfTables tf_tables_;
  std::vector<float> tables_f_;  // the same, rounded to float, for the single-precision kernel
  std::vector<float> bs_f_;
  double s_ref_ = 0;                // the single kernel's scalar origin
  std::vector<double> sh0_, sh1_;   // the batch's scalars relative to it
  light::TfTablesOf<float> tf_tables_f_;
  double inv_unit_;
};

}  // namespace zs
