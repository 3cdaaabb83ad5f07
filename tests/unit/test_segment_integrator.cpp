// The exact integrator's one-piece kernel against brute-force quadrature of
// its defining integrals, over thin, thick, steep and nearly constant pieces:
// the Hermite rule's certified bound and the Gauss–Legendre fallback must
// both hold the colour to ~1e-9 and the transmittance to rounding.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "volume/light_kernel.h"
#include "volume/segment_integrator.h"

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

// The batch kernel (light_kernel.h): the AVX2 and the one-lane build give
// the same bits, and both agree with the scalar kernel within its bound.
TEST(SegmentIntegrator, BatchKernelMatchesScalarBitForBit) {
  const size_t n = 4000;
  std::vector<double> buf(n * 14);
  std::vector<uint8_t> ok1(n), ok4(n);
  auto arrays = [&](double* base, uint8_t* ok) {
    light::PieceArrays a;
    double* b = base;
    auto next = [&] { double* r = b; b += n; return r; };
    for (int k = 0; k < 3; ++k) a.c0[k] = next();
    a.a0 = next();
    for (int k = 0; k < 3; ++k) a.c1[k] = next();
    a.a1 = next();
    a.len = next();
    for (int k = 0; k < 3; ++k) a.rgb[k] = next();
    a.T = next();
    a.ok = ok;
    return a;
  };
  light::PieceArrays A = arrays(buf.data(), ok1.data());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0, 1);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) A.c0[k][i] = u01(rng), A.c1[k][i] = A.c0[k][i] + 0.01 * (u01(rng) - 0.5);
    const double a = u01(rng) * (1 - 1e-6);
    A.a0[i] = a;
    A.a1[i] = i % 7 == 0 ? a : std::clamp(a + 0.05 * (u01(rng) - 0.5), 0.0, 1 - 1e-6);
    A.len[i] = i % 5 == 0 ? 0.0 : std::pow(10.0, -4 + 4 * u01(rng));
  }
  std::vector<double> buf4 = buf;
  light::PieceArrays B = arrays(buf4.data(), ok4.data());
  const double inv_unit = 1 / 0.7;
  light::piece_lights_scalar(A, n, inv_unit);
  if (light::have_avx2()) {
    light::piece_lights_avx2(B, n, inv_unit);
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(A.T[i], B.T[i]) << i;
      ASSERT_EQ(ok1[i], ok4[i]) << i;
      for (int k = 0; k < 3; ++k) ASSERT_EQ(A.rgb[k][i], B.rgb[k][i]) << i;
    }
  } else {
    std::printf("no AVX2 on this CPU: only the one-lane kernel is checked\n");
  }
  double worst = 0;
  size_t accepted = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!ok1[i]) continue;
    ++accepted;
    const double c0[3] = {A.c0[0][i], A.c0[1][i], A.c0[2][i]}, c1[3] = {A.c1[0][i], A.c1[1][i], A.c1[2][i]};
    const SegmentLight l = integrate_linear_piece(c0, A.a0[i], c1, A.a1[i], A.len[i], 0.7);
    worst = std::max(worst, std::abs(l.T - A.T[i]));
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(l.rgb[k] - A.rgb[k][i]));
  }
  std::printf("%zu of %zu pieces taken by the Hermite rule; max difference from the scalar kernel %.2e\n",
              accepted, n, worst);
  EXPECT_GT(accepted, n / 2);
  EXPECT_LE(worst, 2e-9);
}

}  // namespace
}  // namespace zs
