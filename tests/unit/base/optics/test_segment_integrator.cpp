// In base/optics/: beside the integrator; the volume engine's batch kernels are checked against it.
// The exact integrator's one-piece kernel against brute-force quadrature of
// its defining integrals, over thin, thick, steep and nearly constant pieces:
// the Hermite rule's certified bound and the Gauss–Legendre fallback must
// both hold the colour to ~1e-9 and the transmittance to rounding.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "base/optics/light_kernel.h"
#include "render/volume/segment_batch.h"
#include "base/optics/segment_integrator.h"

namespace zs {
namespace {

// Light of a piece where colour and opacity are linear in t over [0, len]:
// I = ∫ c(t) τ(t) T(t) dt, T(t) = exp(-∫τ), τ = -ln(1 - a)/unit, by
// composite 5-point Gauss–Legendre in long double, with the
// optical depth to each node integrated the same way (independent of the
// closed form the kernel uses).
SegmentLight brute(const double c0[3], double a0, const double c1[3], double a1, double len, double unit) {
  static const long double gx[5] = {-0.9061798459386640L, -0.5384693101056831L, 0.0L, 0.5384693101056831L,
                                    0.9061798459386640L};
  static const long double gw[5] = {0.2369268850561891L, 0.4786286704993665L, 0.5688888888888889L,
                                    0.4786286704993665L, 0.2369268850561891L};
  auto tau = [&](long double t) { return -std::log(1.0L - (a0 + (a1 - a0) * t / len)) / unit; };
  auto gl = [&](auto f, long double a, long double b) {
    long double sum = 0;
    for (int k = 0; k < 5; ++k) sum += gw[k] * f(0.5L * (a + b) + 0.5L * (b - a) * gx[k]);
    return sum * 0.5L * (b - a);
  };
  // Panels of at most len/400, and short enough that w = 1 - a changes by at
  // most 1% across one (ln w is steep where w is small).
  const long double dwdt = std::abs((long double)a1 - a0) / len;
  long double D = 0, I[3] = {0, 0, 0};
  for (long double t0 = 0, t1; t0 < len; t0 = t1) {
    const long double w = 1.0L - (a0 + (a1 - a0) * t0 / len);
    t1 = std::min<long double>(len, t0 + std::min<long double>(len / 400.0L, dwdt > 0 ? 0.01L * w / dwdt : len));
    for (int k = 0; k < 3; ++k)
      I[k] += gl([&](long double t) {
                return (c0[k] + (c1[k] - c0[k]) * t / len) * tau(t) * std::exp(-(D + gl(tau, t0, t)));
              }, t0, t1);
    D += gl(tau, t0, t1);
  }
  return {{double(I[0]), double(I[1]), double(I[2])}, double(std::exp(-D))};
}

TEST(SegmentIntegrator, LinearPieceMatchesBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u01(0, 1);
  double worst_rgb = 0, worst_T = 0;
  int cases = 0;
  // (a0, a1) pairs: thin and nearly transparent, equal, nearly equal, steep
  // (0 -> 0.6 inside one piece), nearly opaque; lengths from 1e-4 to 3 units.
  const double pairs[][2] = {{0.0, 0.01},   {0.3, 0.3},   {0.3, 0.3 + 1e-9}, {0.0, 0.6}, {0.6, 0.0},
                             {0.5, 0.55},   {0.9, 0.99},  {0.99, 0.999999},  {0.2, 0.21}, {1e-7, 2e-7}};
  for (const auto& pr : pairs)
    for (double len : {1e-4, 1e-2, 0.1, 0.5, 1.0, 3.0})
      for (int rep = 0; rep < 3; ++rep) {
        double c0[3], c1[3];
        for (int k = 0; k < 3; ++k) c0[k] = u01(rng), c1[k] = u01(rng);
        if (rep == 2)
          for (int k = 0; k < 3; ++k) c1[k] = c0[k] + 1e-3 * (u01(rng) - 0.5);  // a gentle colour ramp
        const double unit = 0.7;
        const SegmentLight got = integrate_linear_piece(c0, pr[0], c1, pr[1], len, unit);
        const SegmentLight want = brute(c0, pr[0], c1, pr[1], len, unit);
        for (int k = 0; k < 3; ++k) worst_rgb = std::max(worst_rgb, std::abs(got.rgb[k] - want.rgb[k]));
        worst_T = std::max(worst_T, std::abs(got.T - want.T));
        ++cases;
      }
  std::printf("%d pieces: max colour error %.2e, max transmittance error %.2e\n", cases, worst_rgb, worst_T);
  EXPECT_LE(worst_rgb, 2e-9);
  EXPECT_LE(worst_T, 1e-11);
}

// The batch kernels (segment_batch.h, light_kernel.h): the one-lane, AVX2
// and AVX-512 builds give the same bits, and agree with the scalar exact
// integrator within its bound, on a short transfer function (looked up from
// registers) and a long one (counted by the caller, gathered), with segments
// inside one interval, across breakpoints, and clamped below and above.
// The single-precision kernel: its one-lane and AVX2 builds give the same
// bits, within `bound` of the double integrator (docs/accuracy.md).
void check_batch_widths(const TransferFunction& tf, double s_lo, double s_hi, uint64_t seed,
                        KernelPrecision prec = KernelPrecision::Double, double bound = 2e-9) {
  const SegmentIntegrator integ(tf, Integrator::Exact);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  struct Seg {
    double s0, s1, len;
  };
  std::vector<Seg> segs;
  for (int i = 0; i < 5000; ++i) {
    const double s0 = s_lo + (s_hi - s_lo) * u01(rng);
    // Mostly short steps in the scalar (one interval), some long ones.
    const double s1 = i % 9 == 0 ? s_lo + (s_hi - s_lo) * u01(rng) : s0 + 0.01 * (s_hi - s_lo) * (u01(rng) - 0.5);
    const double len = i % 5 == 0 ? 0.0 : std::pow(10.0, -4 + 4 * u01(rng));
    segs.push_back({s0, s1, len});
  }
  std::vector<KernelWidth> widths = {KernelWidth::Scalar};
  if (light::have_avx2()) widths.push_back(KernelWidth::AVX2);
  if (light::have_avx512() && prec == KernelPrecision::Double) widths.push_back(KernelWidth::AVX512);
  std::vector<std::vector<SegmentLight>> got(widths.size());
  for (size_t w = 0; w < widths.size(); ++w) {
    SegmentBatch batch(integ, tf, widths[w], prec);
    std::vector<SegmentLight> part;
    for (size_t i = 0; i < segs.size(); ++i) {
      batch.push(uint32_t(i), segs[i].s0, segs[i].s1, segs[i].len);
      if (batch.full() || i + 1 == segs.size()) {
        batch.integrate(&part);
        got[w].insert(got[w].end(), part.begin(), part.end());
      }
    }
    ASSERT_EQ(got[w].size(), segs.size());
  }
  for (size_t w = 1; w < widths.size(); ++w)
    for (size_t i = 0; i < segs.size(); ++i) {
      ASSERT_EQ(got[0][i].T, got[w][i].T) << "width " << int(widths[w]) << " segment " << i;
      for (int k = 0; k < 3; ++k) ASSERT_EQ(got[0][i].rgb[k], got[w][i].rgb[k]) << int(widths[w]) << " " << i;
    }
  double worst = 0;
  for (size_t i = 0; i < segs.size(); ++i) {
    const SegmentLight l = integ.integrate(segs[i].s0, segs[i].s1, segs[i].len);
    worst = std::max(worst, std::abs(l.T - got[0][i].T));
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(l.rgb[k] - got[0][i].rgb[k]));
  }
  std::printf("%zu breakpoints, %zu widths, %s: max difference from the scalar integrator %.2e\n",
              tf.breakpoints().size(), widths.size(), prec == KernelPrecision::Single ? "single" : "double", worst);
  EXPECT_LE(worst, bound);
  if (prec == KernelPrecision::Single) EXPECT_GT(worst, 2e-9) << "floats should show (is the kernel double?)";
}

TEST(SegmentIntegrator, BatchKernelsMatchBitForBit) {
  // Short: three colour points, two opacity points (one table register).
  const TransferFunction short_tf({{0.0, 0.23, 0.30, 0.75}, {0.5, 0.87, 0.87, 0.87}, {1.0, 0.71, 0.02, 0.15}},
                                  {{0.0, 0.0}, {1.0, 0.6}}, 0.3);
  check_batch_widths(short_tf, -0.2, 1.2, 11);
  // Long: 40 opacity points (counted by the caller, tables gathered).
  std::vector<OpacityPoint> op;
  for (int i = 0; i < 40; ++i) op.push_back({i / 39.0, 0.45 + 0.4 * std::sin(i * 0.7)});
  const TransferFunction long_tf({{0.0, 0.1, 0.2, 0.6}, {1.0, 0.9, 0.2, 0.1}}, op, 0.3);
  check_batch_widths(long_tf, -0.1, 1.1, 12);
  // Nine breakpoints: counted in the kernel, gathered by the 8-lane build.
  std::vector<OpacityPoint> op9;
  for (int i = 0; i < 9; ++i) op9.push_back({i / 8.0, 0.1 + 0.1 * i});
  const TransferFunction mid_tf({{0.0, 0.1, 0.2, 0.6}, {1.0, 0.9, 0.2, 0.1}}, op9, 0.3);
  check_batch_widths(mid_tf, -0.1, 1.1, 13);
}

TEST(SegmentIntegrator, SinglePrecisionKernelsMatchBitForBitWithinTheirBound) {
  const TransferFunction short_tf({{0.0, 0.23, 0.30, 0.75}, {0.5, 0.87, 0.87, 0.87}, {1.0, 0.71, 0.02, 0.15}},
                                  {{0.0, 0.0}, {1.0, 0.6}}, 0.3);
  check_batch_widths(short_tf, -0.2, 1.2, 11, KernelPrecision::Single, 1e-6);
  std::vector<OpacityPoint> op;
  for (int i = 0; i < 40; ++i) op.push_back({i / 39.0, 0.45 + 0.4 * std::sin(i * 0.7)});
  const TransferFunction long_tf({{0.0, 0.1, 0.2, 0.6}, {1.0, 0.9, 0.2, 0.1}}, op, 0.3);
  check_batch_widths(long_tf, -0.1, 1.1, 12, KernelPrecision::Single, 1e-6);
  std::vector<OpacityPoint> op9;
  for (int i = 0; i < 9; ++i) op9.push_back({i / 8.0, 0.1 + 0.1 * i});
  const TransferFunction mid_tf({{0.0, 0.1, 0.2, 0.6}, {1.0, 0.9, 0.2, 0.1}}, op9, 0.3);
  check_batch_widths(mid_tf, -0.1, 1.1, 13, KernelPrecision::Single, 1e-6);
  // A scalar range far from zero (a float's spacing at 1000 is 6e-5, a
  // tenth of a percent of this range): the kernel's scalars are relative to
  // the range's middle, so the bound holds here too.
  const TransferFunction offset_tf(
      {{1000.0, 0.23, 0.30, 0.75}, {1000.05, 0.87, 0.87, 0.87}, {1000.1, 0.71, 0.02, 0.15}},
      {{1000.0, 0.0}, {1000.02, 0.3}, {1000.1, 0.6}}, 0.3);
  check_batch_widths(offset_tf, 999.98, 1000.12, 14, KernelPrecision::Single, 1e-6);
}


// The kernels skip the Hermite bound's polynomial when every lane's piece is
// "thin" (light_kernel.h, hermite8_thin_limit). That is only sound if every
// thin piece passes the polynomial test anyway, with room for its rounding:
// check it at the corners of the thin box and at random points inside.
TEST(SegmentIntegrator, ThinPiecesPassTheHermiteBound) {
  using light::Lane1;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u01(0, 1);
  int checked = 0;
  for (double max_dc : {1e-6, 1e-3, 0.05, 0.6, 1.0, 3.0}) {
    const double m = light::hermite8_thin_limit(max_dc);
    ASSERT_GT(m, 0.0);
    double worst = 0;  // largest bound·dc over the tolerance
    for (int i = 0; i < 20000; ++i) {
      // Corners first (each of A, B, r at 0 or its limit), then uniform.
      const double A = i < 8 ? (i & 1 ? m : 0) : m * u01(rng);
      const double B = i < 8 ? (i & 2 ? m * m : 0) : m * m * u01(rng);
      const double r = i < 8 ? (i & 4 ? m : 0) : m * u01(rng);
      const double b = light::hermite8_bound(Lane1(A), Lane1(B), Lane1(r)).v;
      worst = std::max(worst, b * max_dc / light::kHermite8Tolerance);
      ++checked;
    }
    EXPECT_LE(worst, 0.5 + 1e-12) << "max_dc " << max_dc;  // the factor 2 to spare
    EXPECT_GE(worst, 0.49) << "max_dc " << max_dc << ": the limit is needlessly small";
  }
  // A limit that is too large must be caught: twice the limit fails somewhere.
  const double m2 = 2 * light::hermite8_thin_limit(1.0);
  EXPECT_GT(light::hermite8_bound(Lane1(m2), Lane1(m2 * m2), Lane1(m2)).v, light::kHermite8Tolerance);
  EXPECT_EQ(checked, 6 * 20000);
}

}  // namespace
}  // namespace zs
