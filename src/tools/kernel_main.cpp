// zsweep_kernel: the exact integrator's batched segment kernel alone, at
// every vector width this CPU has (segment_batch.h), in ns per segment
// including the apply loop that composites each segment into its pixel. A
// profiling harness like zsweep_frame: it tells how much of a frame's time
// the integration of its segments costs on this machine (docs/performance.md).
//
//   zsweep_kernel MESH.off [segments=1000000] [rounds=5] [len_lo=-3] [len_hi=0]
//
// Segments use the mesh's automatic transfer function (as `zsweep render
// MESH`): s0 uniform over the scalar range, s1 within 1% of the range from
// it (so most lie in one interval, as in a render), lengths log-uniform over
// [10^len_lo, 10^len_hi] unit distances. The transfer function is set by the
// mesh's scalar range and size, so on these synthetic segments every mesh
// gives the same times; the mesh argument keeps to how a render sets it up.
// With ZSWEEP_KERNEL=scalar|avx2 set, only that (capped) width runs. The
// single-precision kernel (scalar-f32, avx2-f32) also prints its largest
// error against the double integrator over these segments.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <vector>

#include "geometry/tets/io/off_io.h"
#include "scene/scene_defaults.h"
#include "render/volume/segment_batch.h"

int main(int argc, char** argv) {
  using namespace zs;
  if (argc < 2) {
    std::fprintf(stderr, "usage: zsweep_kernel MESH.off [segments] [rounds] [len_lo] [len_hi]\n");
    return 2;
  }
  try {
    const TetMesh mesh = read_off(argv[1]);
    const size_t n = argc > 2 ? size_t(std::atof(argv[2])) : 1000000;
    const int rounds = argc > 3 ? std::atoi(argv[3]) : 5;
    const double lg_lo = argc > 4 ? std::atof(argv[4]) : -3, lg_hi = argc > 5 ? std::atof(argv[5]) : 0;
    if (n < 1 || rounds < 1 || !(lg_lo <= lg_hi)) {
      std::fprintf(stderr, "zsweep_kernel: need segments >= 1, rounds >= 1 and len_lo <= len_hi\n");
      return 2;
    }
    const TransferFunction tf = default_transfer_function(mesh);
    const SegmentIntegrator integ(tf, Integrator::Exact);
    const double lo = tf.breakpoints().front(), hi = tf.breakpoints().back(), unit = tf.unit_distance();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u01(0, 1);
    struct Seg {
      double s0, s1, len;
    };
    std::vector<Seg> segs(n);
    for (Seg& g : segs) {
      g.s0 = lo + (hi - lo) * u01(rng);
      g.s1 = std::clamp(g.s0 + 0.01 * (hi - lo) * (u01(rng) - 0.5), lo, hi);
      g.len = unit * std::pow(10.0, lg_lo + (lg_hi - lg_lo) * u01(rng));
    }
    std::vector<PixelLight> px(4096);
    std::printf("%zu segments, %zu transfer-function breakpoints\n", n, tf.breakpoints().size());
    std::vector<KernelWidth> widths = {KernelWidth::Scalar};
    if (light::have_avx2()) widths.push_back(KernelWidth::AVX2);
    if (light::have_avx512()) widths.push_back(KernelWidth::AVX512);
    for (KernelPrecision prec : {KernelPrecision::Double, KernelPrecision::Single})
      for (KernelWidth w : widths) {
        if (std::getenv("ZSWEEP_KERNEL") && w != best_kernel_width()) continue;  // the capped width only
        if (prec == KernelPrecision::Single && w == KernelWidth::AVX512) continue;  // the AVX2 kernel
        const bool single = prec == KernelPrecision::Single;
        SegmentBatch batch(integ, tf, w, prec);
        double best = 1e300;
        for (int r = 0; r < rounds; ++r) {
          for (PixelLight& p : px) p.reset();
          const auto t0 = std::chrono::steady_clock::now();
          for (size_t i = 0; i < n; ++i) {
            if (batch.full()) batch.flush(px.data());
            batch.push(uint32_t(i & 4095), segs[i].s0, segs[i].s1, segs[i].len);
          }
          batch.flush(px.data());
          const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
          best = std::min(best, ns / double(n));
        }
        double sum = 0;
        for (const PixelLight& p : px) sum += p.rgb[0] + p.T;
        const char* name = w == KernelWidth::Scalar ? (single ? "scalar-f32" : "scalar")
                           : w == KernelWidth::AVX2 ? (single ? "avx2-f32" : "avx2")
                                                    : "avx512";
        std::printf("%-10s %6.2f ns per segment (best of %d; checksum %.9g)", name, best, rounds, sum);
        if (single) {
          // The single-precision kernel's error against the double integrator, segment by segment.
          double worst_rgb = 0, worst_T = 0;
          std::vector<SegmentLight> out;
          for (size_t i0 = 0; i0 < n; i0 += SegmentBatch::kCapacity) {
            const size_t i1 = std::min(n, i0 + SegmentBatch::kCapacity);
            for (size_t i = i0; i < i1; ++i) batch.push(0, segs[i].s0, segs[i].s1, segs[i].len);
            batch.integrate(&out);
            for (size_t i = i0; i < i1; ++i) {
              const SegmentLight ref = integ.integrate(segs[i].s0, segs[i].s1, segs[i].len);
              for (int k = 0; k < 3; ++k) worst_rgb = std::max(worst_rgb, std::abs(out[i - i0].rgb[k] - ref.rgb[k]));
              worst_T = std::max(worst_T, std::abs(out[i - i0].T - ref.T));
            }
          }
          std::printf("; largest error against double: rgb %.2e, T %.2e", worst_rgb, worst_T);
        }
        std::printf("\n");
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "zsweep_kernel: %s\n", e.what());
    return 1;
  }
  return 0;
}
