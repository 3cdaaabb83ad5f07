// The exact integrator's one-piece light (segment_integrator.cpp,
// integrate_linear_piece) written once over a lane type V, so the same
// arithmetic runs on one double (V = Lane1), four (Lane4, AVX2) or eight
// (Lane8, AVX-512) and gives bit-identical results every way: only IEEE +,
// -, *, /, fused multiply-add where written (fmadd: one rounding, as
// std::fma; never contracted by the compiler) and exact bit manipulation, in
// the same order, and table lookups (exact).
//
// exp and log are our own (Cody–Waite reduction and Taylor / atanh series,
// ~1 ulp) because libm's are scalar. Inputs are those of a piece: w = 1 - a
// in [1e-6, 1], and exp arguments <= 0 (clamped at -700, T < 1e-304).
//
// The same code also runs on floats (Lane1f, Lane8f: the single-precision
// kernel, eight segments per AVX2 vector), with the few constants that
// depend on the precision in Precision<float> and its own, looser rule
// tolerance (kSingleTolerance); docs/accuracy.md states its error.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace zs::light {

// What depends on a lane type's precision (V::Scalar).
template <class T>
struct Precision;
template <>
struct Precision<double> {
  static constexpr double exp_min = -700.0;   // e^-700 > 0 and normal
  static constexpr double series_below = 1e-2;  // |q| below which the mean of ln w uses its series
};
template <>
struct Precision<float> {
  static constexpr double exp_min = -87.0;  // 2^-126 (the smallest normal float) < e^-87
  // The difference quotient loses ~eps/|q| to cancellation: in float the
  // series (error < q^8/9) takes over earlier.
  static constexpr double series_below = 0.1;
};
template <class V>
constexpr bool kIsFloat = std::is_same_v<typename V::Scalar, float>;

// Inputs of one piece, per lane; outputs rgb, T and `ok` (false where the
// Hermite rule's bound fails: the caller integrates that piece itself).
template <class V>
struct PieceIn {
  V c0[3], a0, c1[3], a1, len;
};
template <class V>
struct PieceOut {
  V rgb[3], T;
  typename V::Mask ok;
};

template <class V>
inline V exp_neg(V x) {  // e^x for x <= 0
  x = max(x, V(Precision<typename V::Scalar>::exp_min));
  const V n = round_int(x * V(1.4426950408889634));  // x / ln 2
  // ln 2 split so that n·ln2_hi is exact for |n| < 2^11.
  const V r = fmadd(n, V(-1.9082149292705877e-10), fmadd(n, V(-0.6931471803691238), x));
  if constexpr (kIsFloat<V>) {
    // Floats: Taylor to r^7 (next term < 5.6e-9 relative, a tenth of a float's ulp).
    const V r2 = r * r, r4 = r2 * r2;
    const V p01 = V(1.0) + r, p23 = fmadd(V(1.0 / 6.0), r, V(0.5));
    const V p45 = fmadd(V(1.0 / 120.0), r, V(1.0 / 24.0)), p67 = fmadd(V(1.0 / 5040.0), r, V(1.0 / 720.0));
    return fmadd(r4, fmadd(r2, p67, p45), fmadd(r2, p23, p01)) * pow2_int(n);
  }
  // |r| <= 0.347: Taylor to r^11 (next term < 7e-15 relative), evaluated by
  // Estrin's scheme: a few short dependency chains instead of one long one.
  const V r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const V p01 = V(1.0) + r, p23 = fmadd(V(1.0 / 6.0), r, V(0.5));
  const V p45 = fmadd(V(1.0 / 120.0), r, V(1.0 / 24.0)), p67 = fmadd(V(1.0 / 5040.0), r, V(1.0 / 720.0));
  const V p89 = fmadd(V(1.0 / 362880.0), r, V(1.0 / 40320.0));
  const V pab = fmadd(V(1.0 / 39916800.0), r, V(1.0 / 3628800.0));
  const V p03 = fmadd(r2, p23, p01), p47 = fmadd(r2, p67, p45), p8b = fmadd(r2, pab, p89);
  const V p = fmadd(r8, p8b, fmadd(r4, p47, p03));
  return p * pow2_int(n);
}

// ln w0 and ln w1 for w in (0, 1], normal, sharing one division.
template <class V>
inline void log_pos2(V w0, V w1, V* L0, V* L1) {
  V e0, m0, e1, m1;
  split_exponent(w0, &e0, &m0);  // w = m·2^e, m in [1, 2)
  split_exponent(w1, &e1, &m1);
  const typename V::Mask big0 = m0 > V(1.4142135623730951), big1 = m1 > V(1.4142135623730951);
  m0 = select(big0, m0 * V(0.5), m0);
  e0 = select(big0, e0 + V(1.0), e0);
  m1 = select(big1, m1 * V(0.5), m1);
  e1 = select(big1, e1 + V(1.0), e1);
  // ln m = 2·atanh(f), f = (m - 1)/(m + 1), |f| <= 0.1716: series to f^17
  // (next term < 2e-16 relative), Estrin in f².
  const V a0 = m0 + V(1.0), a1 = m1 + V(1.0), inv = V(1.0) / (a0 * a1);
  const V f[2] = {(m0 - V(1.0)) * a1 * inv, (m1 - V(1.0)) * a0 * inv};
  const V e[2] = {e0, e1};
  V* out[2] = {L0, L1};
  for (int k = 0; k < 2; ++k) {
    if constexpr (kIsFloat<V>) {
      // Floats: the series to f^9 (next term < 2e-9 relative).
      const V f2 = f[k] * f[k], f4 = f2 * f2;
      const V s = fmadd(f4, fmadd(f4, V(1.0 / 9), fmadd(V(1.0 / 7), f2, V(1.0 / 5))), fmadd(V(1.0 / 3), f2, V(1.0)));
      *out[k] = fmadd(e[k], V(0.6931471803691238), fmadd(e[k], V(1.9082149292705877e-10), V(2.0) * f[k] * s));
      continue;
    }
    const V f2 = f[k] * f[k], f4 = f2 * f2, f8 = f4 * f4;
    const V s01 = fmadd(V(1.0 / 3), f2, V(1.0)), s23 = fmadd(V(1.0 / 7), f2, V(1.0 / 5));
    const V s45 = fmadd(V(1.0 / 11), f2, V(1.0 / 9)), s67 = fmadd(V(1.0 / 15), f2, V(1.0 / 13));
    const V s = fmadd(f8, fmadd(f8, V(1.0 / 17), fmadd(f4, s67, s45)), fmadd(f4, s23, s01));
    const V ln_m = V(2.0) * f[k] * s;
    *out[k] = fmadd(e[k], V(0.6931471803691238), fmadd(e[k], V(1.9082149292705877e-10), ln_m));
  }
}

// The mean of T over a piece by the two-point Hermite rule, exact for
// degree 7 (segment_integrator.cpp derives it): with g = -kappa·ln w,
// m = -g' = kappa·dw/w and n = g'' = kappa·(dw/w)² at both ends,
//   f' = -g f,  f'' = (g² + m) f,  f''' = (-g³ - 3g·m - n) f.
template <class V>
inline V hermite8_mean(V g0, V g1, V m0, V m1, V n0, V n1, V T) {
  const V f1p = V(0.0) - g0, f2p = (V(0.0) - g1) * T;
  const V f1pp = fmadd(g0, g0, m0), f2pp = fmadd(g1, g1, m1) * T;
  const V f1ppp = V(0.0) - fmadd(g0, fmadd(g0, g0, V(3.0) * m0), n0);
  const V f2ppp = (V(0.0) - fmadd(g1, fmadd(g1, g1, V(3.0) * m1), n1)) * T;
  return fmadd(V(1.0 / 1680), f1ppp - f2ppp,
               fmadd(V(1.0 / 84), f1pp + f2pp, fmadd(V(3.0 / 28), f1p - f2p, V(0.5) * (V(1.0) + T))));
}

// The rule's error is f⁽⁸⁾/25401600 with |f⁽⁸⁾| ≤ Y8(a, b, b·r, 2b·r², ...,
// 720b·r⁶): the complete Bell polynomial on bounds of D's derivatives
// (a = max g, r = |dw|/min w, b = kappa·r, |g⁽ᵏ⁾| ≤ (k-1)!·b·r^(k-1)).
template <class V>
inline V hermite8_bound(V A, V B, V r) {
  // A bound, not a result: fused or not, it only decides which rule runs.
  const V A2 = A * A, B2 = B * B, A2B = A2 * B, B3 = B2 * B;
  const V r0 = fmadd(A2, fmadd(A2, fmadd(A2, fmadd(V(28.0), B, A2), V(210.0) * B2), V(420.0) * B3), V(105.0) * B2 * B2);
  const V r1 = A * fmadd(A2, fmadd(V(56.0), A2B, V(560.0) * B2), V(840.0) * B3);
  const V r2 = fmadd(A2, fmadd(V(140.0), A2B, V(1120.0) * B2), V(700.0) * B3);
  const V r3 = A * fmadd(V(336.0), A2B, V(1568.0) * B2);
  const V r4 = fmadd(V(672.0), A2B, V(1148.0) * B2);
  const V r5 = B * fmadd(V(960.0), A, V(720.0) * r);
  return fmadd(r, fmadd(r, fmadd(r, fmadd(r, fmadd(r, r5, r4), r3), r2), r1), r0);
}
// The rule is used where bound·max|c1 - c0| <= 1e-9·25401600.
constexpr double kHermite8Tolerance = 1e-9 * 25401600.0;
// The single-precision kernel's: 1e-7 per piece, about a float's rounding.
constexpr double kSingleTolerance = 1e-7 * 25401600.0;
// Every term of the bound is a coefficient times A^i·B^j·r^k with
// i + 2j + k = 8, so where A <= m, B <= m² and r <= m it is at most the sum
// of the coefficients times m^8.
constexpr double kHermite8CoefficientSum = 9584.0;
// The m below which every piece passes the bound with a factor 2 to spare
// (so the polynomial, rounded, would pass it too): m^8 = tolerance /
// (2 · 9584 · largest |c1 - c0| of a piece); "thin" pieces (a small optical
// depth and little change of opacity) skip the polynomial.
inline double hermite8_thin_limit(double max_dc, double tolerance = kHermite8Tolerance) {
  if (!(max_dc > 0)) return 1e3;
  return std::fmin(1e3, std::pow(tolerance / (2.0 * kHermite8CoefficientSum * max_dc), 0.125));
}

// One piece: colour and opacity linear, optical depth in closed form, the
// mean of T by the Hermite rule where its bound allows.
// thin: hermite8_thin_limit for this tolerance and the pieces' colours, or
// 0; when every lane's piece is that thin, `ok` needs no polynomial.
template <class V>
inline void piece_light(const PieceIn<V>& in, double inv_unit, PieceOut<V>* out,
                        double tolerance = kHermite8Tolerance, double thin = 0.0) {
  const V one(1.0);
  const V w0 = one - in.a0, w1 = one - in.a1;
  V L0, L1;
  log_pos2(w0, w1, &L0, &L1);
  const V kappa = in.len * V(inv_unit);
  // Mean of ln w over [w0, w1]: series in q where the difference cancels.
  const V d = w1 - w0, q = d / (w0 + w1), q2 = q * q;
  const V series = fmadd(q2, fmadd(q2, fmadd(q2, V(1.0 / 7), V(1.0 / 5)), V(1.0 / 3)), V(0.5) * (L0 + L1));
  const V divided = (w1 * L1 - w0 * L0) / d - one;
  const V mean = select(abs(q) < V(Precision<typename V::Scalar>::series_below), series, divided);
  const V T = exp_neg(kappa * mean);
  const V g0 = V(0.0) - kappa * L0, g1 = V(0.0) - kappa * L1;
  const V inv_w01 = one / (w0 * w1), inv_w0 = w1 * inv_w01, inv_w1 = w0 * inv_w01;
  const V A = max(g0, g1), r = abs(d) * max(inv_w0, inv_w1), B = kappa * r;
  V dc[3];
  for (int k = 0; k < 3; ++k) dc[k] = in.c1[k] - in.c0[k];
  const auto is_thin = V::mask_and(V::mask_and(A <= V(thin), B <= V(thin * thin)), r <= V(thin));
  if (V::all(is_thin)) {
    out->ok = is_thin;  // all true: the bound passes (see hermite8_thin_limit)
  } else {
    V dcmax(0.0);
    for (int k = 0; k < 3; ++k) dcmax = max(dcmax, abs(dc[k]));
    out->ok = dcmax * hermite8_bound(A, B, r) <= V(tolerance);
  }
  const V h0 = d * inv_w0, h1 = d * inv_w1;
  const V Jm = hermite8_mean(g0, g1, kappa * h0, kappa * h1, kappa * h0 * h0, kappa * h1 * h1, T);
  for (int k = 0; k < 3; ++k) out->rgb[k] = fmadd(dc[k], Jm, fnmadd(in.c1[k], T, in.c0[k]));
  out->T = T;
}

// A transfer function as per-interval tables the batch kernels index by
// n = (breakpoints at or below s) = k + 1, k = TransferFunction::interval(s)
// in [-1, nb - 1]. Entry n holds the interval's left breakpoint, 1/width, and
// rgba at its left end with the slope to its right end (rgba_in's arithmetic:
// c = lo + t·d, t = (s - bs)·inv_w); the two clamped ends (n = 0, n = nb) hold
// the end value, with t forced to 0. Every table has at least 8 entries
// (zero-padded), so an 8-lane kernel can hold one in a register. T: the
// kernel's precision (float tables for the single-precision kernel).
template <class T>
struct TfTablesOf {
  int nb = 0;            // breakpoints
  const T* bs = nullptr; // the nb breakpoints, for counting
  const T* cut = nullptr;  // entry n >= 1: breakpoint n - 1 (where interval n starts)
  const T* left = nullptr;
  const T* inv_w = nullptr;
  const T* lo[4] = {};
  const T* d[4] = {};
  double tolerance = kHermite8Tolerance;  // the rule's, per segment
  double thin = 0;  // hermite8_thin_limit of the largest colour slope |d[0..2]| at that tolerance
};
using TfTables = TfTablesOf<double>;

// A batch of segments, structure of arrays (n a multiple of the lane count).
// n0/n1: the breakpoint counts of s0/s1, precomputed by the caller for long
// transfer functions (null: the kernel counts, for nb <= kCountInKernel).
struct SegmentSoA {
  const double *s0, *s1, *len;
  const double *n0 = nullptr, *n1 = nullptr;
  double* rgb[3];
  double* T;
  uint8_t* ok;  // 0: the caller integrates this segment itself
};
constexpr int kCountInKernel = 16;

// The breakpoint counts n of segments i.. (light_kernel's table index).
template <class V>
inline void breakpoint_counts(const TfTablesOf<typename V::Scalar>& tf, const SegmentSoA& q, size_t i, V s0, V s1, V* n0, V* n1) {
  if (q.n0) {
    *n0 = V::load(q.n0 + i);
    *n1 = V::load(q.n1 + i);
    return;
  }
  // !(s < b) counts b <= s, and counts NaN above every breakpoint, as
  // TransferFunction::interval does.
  const V one(1.0);
  *n0 = *n1 = V(0.0);
  for (int j = 0; j < tf.nb; ++j) {
    const V b(tf.bs[j]);
    *n0 = select(not_less(s0, b), *n0 + one, *n0);
    *n1 = select(not_less(s1, b), *n1 + one, *n1);
  }
}

// Colour and opacity at scalars sa and sb, both in (or at the ends of)
// interval n: the piece's two ends.
template <class V>
inline void piece_ends(const TfTablesOf<typename V::Scalar>& tf, V n, V sa, V sb, PieceIn<V>* in) {
  const int entries = tf.nb + 1;
  const V zero(0.0);
  const auto inside = V::mask_and(n >= V(1.0), n <= V(double(tf.nb - 1)));
  const V left = V::lookup(tf.left, n, entries), inv_w = V::lookup(tf.inv_w, n, entries);
  const V t0 = select(inside, (sa - left) * inv_w, zero), t1 = select(inside, (sb - left) * inv_w, zero);
  V lo = V::lookup(tf.lo[3], n, entries), d = V::lookup(tf.d[3], n, entries);
  in->a0 = lo + t0 * d;
  in->a1 = lo + t1 * d;
  for (int k = 0; k < 3; ++k) {
    lo = V::lookup(tf.lo[k], n, entries);
    d = V::lookup(tf.d[k], n, entries);
    in->c0[k] = lo + t0 * d;
    in->c1[k] = lo + t1 * d;
  }
}

// Segments i .. i + lanes - 1: both ends' colour and opacity from the tables,
// then piece_light. `ok` is false where the segment crosses a breakpoint
// (several pieces) or the Hermite bound fails.
template <class V>
inline void segment_light(const TfTablesOf<typename V::Scalar>& tf, const SegmentSoA& q, size_t i, double inv_unit) {
  const V s0 = V::load(q.s0 + i), s1 = V::load(q.s1 + i);
  V n0, n1;
  breakpoint_counts(tf, q, i, s0, s1, &n0, &n1);
  PieceIn<V> in;
  piece_ends(tf, n0, s0, s1, &in);
  in.len = V::load(q.len + i);
  PieceOut<V> out;
  piece_light(in, inv_unit, &out, tf.tolerance, tf.thin);
  for (int k = 0; k < 3; ++k) out.rgb[k].store(q.rgb[k] + i);
  out.T.store(q.T + i);
  V::store_mask(q.ok + i, V::mask_and(out.ok, n0 == n1));
}

// The segments segment_light could not take, in 2·parts pieces: cut at the
// breakpoint crossed when the ends lie in neighbouring intervals (else at
// the middle), each half cut again into `parts` equal pieces, each piece by
// piece_light within 1/(2·parts) of the tolerance (so the segment stays
// within it), composited front to back. `ok` stays false where the ends lie
// further apart or a piece's bound still fails.
template <class V>
inline void segment_light_split(const TfTablesOf<typename V::Scalar>& tf, const SegmentSoA& q, size_t i, double inv_unit, int parts) {
  const V one(1.0), half(0.5);
  const V s0 = V::load(q.s0 + i), s1 = V::load(q.s1 + i), len = V::load(q.len + i);
  V n0, n1;
  breakpoint_counts(tf, q, i, s0, s1, &n0, &n1);
  const auto same = n0 == n1;
  const V cut = select(same, half * (s0 + s1), V::lookup(tf.cut, max(n0, n1), tf.nb + 1));
  const V frac = select(same, half, (cut - s0) / (s1 - s0));
  auto ok = abs(n1 - n0) <= one;
  const double tol = tf.tolerance / double(2 * parts);
  V rgb[3] = {V(0.0), V(0.0), V(0.0)}, T = one;
  for (int h = 0; h < 2; ++h) {
    const V sa = h == 0 ? s0 : cut, sb = h == 0 ? cut : s1, n = h == 0 ? n0 : n1;
    const V hlen = (h == 0 ? frac : one - frac) * len;
    for (int j = 0; j < parts; ++j) {
      const V pa = j == 0 ? sa : sa + (sb - sa) * V(double(j) / parts);
      const V pb = j + 1 == parts ? sb : sa + (sb - sa) * V(double(j + 1) / parts);
      PieceIn<V> in;
      piece_ends(tf, n, pa, pb, &in);
      in.len = hlen * V(1.0 / parts);
      PieceOut<V> out;
      piece_light(in, inv_unit, &out, tol);
      for (int k = 0; k < 3; ++k) rgb[k] = rgb[k] + T * out.rgb[k];
      T = T * out.T;
      ok = V::mask_and(ok, out.ok);
    }
  }
  for (int k = 0; k < 3; ++k) rgb[k].store(q.rgb[k] + i);
  T.store(q.T + i);
  V::store_mask(q.ok + i, ok);
}

// The batch over n segments (a multiple of 16), one lane width each;
// parts = 0: segment_light, else segment_light_split with that many parts.
void segment_lights_scalar(const TfTables& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts);
void segment_lights_avx2(const TfTables& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts);  // AVX2
void segment_lights_avx512(const TfTables& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts);  // AVX-512F
bool have_avx2();
bool have_avx512();
// The single-precision kernel (rgb and T rounded to float, error in docs/accuracy.md).
void segment_lights_scalar_f32(const TfTablesOf<float>& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts);
void segment_lights_avx2_f32(const TfTablesOf<float>& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts);

// One value per lane: Lane1 (double) is the reference every vector width
// matches bit for bit, Lane1f (float) the single-precision kernel's (Lane8f
// in light_kernel_avx2.cpp gives the same bits). Loads and stores convert
// from and to the batch's doubles.
template <class T>
struct LaneOne {
  using Scalar = T;
  using Mask = bool;
  using Bits = std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>;
  static constexpr int kMantissa = sizeof(T) == 8 ? 52 : 23;  // fraction bits
  static constexpr int kBias = sizeof(T) == 8 ? 1023 : 127;
  T v;
  LaneOne() = default;
  explicit LaneOne(double x) : v(T(x)) {}
  friend LaneOne operator+(LaneOne a, LaneOne b) { return LaneOne(a.v + b.v); }
  friend LaneOne operator-(LaneOne a, LaneOne b) { return LaneOne(a.v - b.v); }
  friend LaneOne operator*(LaneOne a, LaneOne b) { return LaneOne(a.v * b.v); }
  friend LaneOne operator/(LaneOne a, LaneOne b) { return LaneOne(a.v / b.v); }
  // a·b + c and c - a·b, rounded once (std::fma is exact in every build).
  friend LaneOne fmadd(LaneOne a, LaneOne b, LaneOne c) { return LaneOne(std::fma(a.v, b.v, c.v)); }
  friend LaneOne fnmadd(LaneOne a, LaneOne b, LaneOne c) { return LaneOne(std::fma(-a.v, b.v, c.v)); }
  friend bool operator<(LaneOne a, LaneOne b) { return a.v < b.v; }
  friend bool operator>(LaneOne a, LaneOne b) { return a.v > b.v; }
  friend bool operator<=(LaneOne a, LaneOne b) { return a.v <= b.v; }
  friend bool operator>=(LaneOne a, LaneOne b) { return a.v >= b.v; }
  friend bool operator==(LaneOne a, LaneOne b) { return a.v == b.v; }
  friend bool not_less(LaneOne a, LaneOne b) { return !(a.v < b.v); }
  static LaneOne load(const double* p) { return LaneOne(*p); }
  void store(double* p) const { *p = double(v); }
  static bool mask_and(bool a, bool b) { return a && b; }
  static bool all(bool m) { return m; }
  static void store_mask(uint8_t* p, bool m) { *p = m; }
  static LaneOne lookup(const T* table, LaneOne n, int) { return LaneOne(table[size_t(n.v)]); }
  // max as the AVX instructions define it (second operand on NaN).
  friend LaneOne max(LaneOne a, LaneOne b) { return LaneOne(a.v > b.v ? a.v : b.v); }
  friend LaneOne abs(LaneOne a) {
    Bits u;
    std::memcpy(&u, &a.v, sizeof(T));
    u &= ~(Bits(1) << (8 * sizeof(T) - 1));
    std::memcpy(&a.v, &u, sizeof(T));
    return a;
  }
  friend LaneOne select(bool m, LaneOne a, LaneOne b) { return m ? a : b; }
  // Round to the nearest integer (ties to even) by the 1.5·2^mantissa trick,
  // as the vector versions do.
  friend LaneOne round_int(LaneOne x) {
    const T c = T(1.5) * T(Bits(1) << kMantissa);
    return LaneOne((x.v + c) - c);
  }
  friend LaneOne pow2_int(LaneOne n) {  // 2^n, n integral in the normal exponent range
    const Bits u = Bits(int64_t(n.v) + kBias) << kMantissa;
    T d;
    std::memcpy(&d, &u, sizeof(T));
    return LaneOne(d);
  }
  friend void split_exponent(LaneOne w, LaneOne* e, LaneOne* m) {
    Bits u;
    std::memcpy(&u, &w.v, sizeof(T));
    e->v = T(int64_t(u >> kMantissa) - kBias);
    u = (u & ((Bits(1) << kMantissa) - 1)) | (Bits(kBias) << kMantissa);
    std::memcpy(&m->v, &u, sizeof(T));
  }
};
using Lane1 = LaneOne<double>;
using Lane1f = LaneOne<float>;

}  // namespace zs::light
