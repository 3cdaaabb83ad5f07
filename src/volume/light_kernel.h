// The exact integrator's one-piece light (segment_integrator.cpp,
// integrate_linear_piece) written once over a lane type V, so the same
// arithmetic runs on one double (V = Lane1) or four (V = Lane4, AVX2) and
// gives bit-identical results either way: only IEEE +, -, *, / and exact
// bit manipulation, in the same order, no contraction into FMA.
//
// exp and log are our own (Cody–Waite reduction and Taylor / atanh series,
// ~1 ulp) because libm's are scalar. Inputs are those of a piece: w = 1 - a
// in [1e-6, 1], and exp arguments <= 0 (clamped at -700, T < 1e-304).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace zs::light {

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
  x = max(x, V(-700.0));
  const V n = round_int(x * V(1.4426950408889634));  // x / ln 2
  // ln 2 split so that n·ln2_hi is exact for |n| < 2^11.
  const V r = (x - n * V(0.6931471803691238)) - n * V(1.9082149292705877e-10);
  // |r| <= 0.347: Taylor to r^13 (next term < 4e-18).
  V p = V(1.0 / 6227020800.0);
  p = p * r + V(1.0 / 479001600.0);
  p = p * r + V(1.0 / 39916800.0);
  p = p * r + V(1.0 / 3628800.0);
  p = p * r + V(1.0 / 362880.0);
  p = p * r + V(1.0 / 40320.0);
  p = p * r + V(1.0 / 5040.0);
  p = p * r + V(1.0 / 720.0);
  p = p * r + V(1.0 / 120.0);
  p = p * r + V(1.0 / 24.0);
  p = p * r + V(1.0 / 6.0);
  p = p * r + V(0.5);
  p = p * r + V(1.0);
  p = p * r + V(1.0);
  return p * pow2_int(n);
}

template <class V>
inline V log_pos(V w) {  // ln w for w in (0, 1], normal
  V e, m;
  split_exponent(w, &e, &m);  // w = m·2^e, m in [1, 2)
  const typename V::Mask big = m > V(1.4142135623730951);
  m = select(big, m * V(0.5), m);
  e = select(big, e + V(1.0), e);
  // ln m = 2·atanh(f), f = (m - 1)/(m + 1), |f| <= 0.1716: series to f^23.
  const V f = (m - V(1.0)) / (m + V(1.0)), f2 = f * f;
  V s = V(1.0 / 23);
  s = s * f2 + V(1.0 / 21);
  s = s * f2 + V(1.0 / 19);
  s = s * f2 + V(1.0 / 17);
  s = s * f2 + V(1.0 / 15);
  s = s * f2 + V(1.0 / 13);
  s = s * f2 + V(1.0 / 11);
  s = s * f2 + V(1.0 / 9);
  s = s * f2 + V(1.0 / 7);
  s = s * f2 + V(1.0 / 5);
  s = s * f2 + V(1.0 / 3);
  s = s * f2 + V(1.0);
  const V ln_m = V(2.0) * f * s;
  return e * V(0.6931471803691238) + (e * V(1.9082149292705877e-10) + ln_m);
}

// The mean of T over a piece by the two-point Hermite rule, exact for
// degree 7 (segment_integrator.cpp derives it): with g = -kappa·ln w,
// m = -g' = kappa·dw/w and n = g'' = kappa·(dw/w)² at both ends,
//   f' = -g f,  f'' = (g² + m) f,  f''' = (-g³ - 3g·m - n) f.
template <class V>
inline V hermite8_mean(V g0, V g1, V m0, V m1, V n0, V n1, V T) {
  const V f1p = V(0.0) - g0, f2p = (V(0.0) - g1) * T;
  const V f1pp = g0 * g0 + m0, f2pp = (g1 * g1 + m1) * T;
  const V f1ppp = V(0.0) - (g0 * g0 * g0 + V(3.0) * g0 * m0 + n0);
  const V f2ppp = (V(0.0) - (g1 * g1 * g1 + V(3.0) * g1 * m1 + n1)) * T;
  return V(0.5) * (V(1.0) + T) + V(3.0 / 28) * (f1p - f2p) + V(1.0 / 84) * (f1pp + f2pp) +
         V(1.0 / 1680) * (f1ppp - f2ppp);
}

// The rule's error is f⁽⁸⁾/25401600 with |f⁽⁸⁾| ≤ Y8(a, b, b·r, 2b·r², ...,
// 720b·r⁶): the complete Bell polynomial on bounds of D's derivatives
// (a = max g, r = |dw|/min w, b = kappa·r, |g⁽ᵏ⁾| ≤ (k-1)!·b·r^(k-1)).
template <class V>
inline V hermite8_bound(V A, V B, V r) {
  const V A2 = A * A, B2 = B * B;
  return A2 * (A2 * (A2 * (A2 + V(28.0) * B) + V(210.0) * B2) + V(420.0) * B2 * B) + V(105.0) * B2 * B2 +
         r * (A * (A2 * (V(56.0) * A2 * B + V(560.0) * B2) + V(840.0) * B2 * B) +
              r * (A2 * (V(140.0) * A2 * B + V(1120.0) * B2) + V(700.0) * B2 * B +
                   r * (A * (V(336.0) * A2 * B + V(1568.0) * B2) +
                        r * (V(672.0) * A2 * B + V(1148.0) * B2 + r * (V(960.0) * A * B + V(720.0) * B * r)))));
}
// The rule is used where bound·max|c1 - c0| <= 1e-9·25401600.
constexpr double kHermite8Tolerance = 1e-9 * 25401600.0;

// One piece: colour and opacity linear, optical depth in closed form, the
// mean of T by the Hermite rule where its bound allows.
template <class V>
inline void piece_light(const PieceIn<V>& in, double inv_unit, PieceOut<V>* out) {
  const V one(1.0);
  const V w0 = one - in.a0, w1 = one - in.a1;
  const V L0 = log_pos(w0), L1 = log_pos(w1);
  const V kappa = in.len * V(inv_unit);
  // Mean of ln w over [w0, w1]: series in q where the difference cancels.
  const V d = w1 - w0, q = d / (w0 + w1), q2 = q * q;
  const V series = V(0.5) * (L0 + L1) + q2 * (V(1.0 / 3) + q2 * (V(1.0 / 5) + q2 * V(1.0 / 7)));
  const V divided = (w1 * L1 - w0 * L0) / d - one;
  const V mean = select(abs(q) < V(1e-2), series, divided);
  const V T = exp_neg(kappa * mean);
  const V g0 = V(0.0) - kappa * L0, g1 = V(0.0) - kappa * L1;
  const V inv_w0 = one / w0, inv_w1 = one / w1;
  const V A = max(g0, g1), r = abs(d) * max(inv_w0, inv_w1), B = kappa * r;
  V dc[3], dcmax(0.0);
  for (int k = 0; k < 3; ++k) {
    dc[k] = in.c1[k] - in.c0[k];
    dcmax = max(dcmax, abs(dc[k]));
  }
  out->ok = dcmax * hermite8_bound(A, B, r) <= V(kHermite8Tolerance);
  const V h0 = d * inv_w0, h1 = d * inv_w1;
  const V Jm = hermite8_mean(g0, g1, kappa * h0, kappa * h1, kappa * h0 * h0, kappa * h1 * h1, T);
  for (int k = 0; k < 3; ++k) out->rgb[k] = in.c0[k] - in.c1[k] * T + dc[k] * Jm;
  out->T = T;
}

// Structure-of-arrays pieces for the batch kernels (n a multiple of 4).
struct PieceArrays {
  double* c0[3];
  double* a0;
  double* c1[3];
  double* a1;
  double* len;
  double* rgb[3];
  double* T;
  uint8_t* ok;
};
void piece_lights_scalar(const PieceArrays& p, size_t n, double inv_unit);
void piece_lights_avx2(const PieceArrays& p, size_t n, double inv_unit);  // needs AVX2 at run time
bool have_avx2();

// One double per lane.
struct Lane1 {
  using Mask = bool;
  double v;
  Lane1() = default;
  explicit Lane1(double x) : v(x) {}
  friend Lane1 operator+(Lane1 a, Lane1 b) { return Lane1(a.v + b.v); }
  friend Lane1 operator-(Lane1 a, Lane1 b) { return Lane1(a.v - b.v); }
  friend Lane1 operator*(Lane1 a, Lane1 b) { return Lane1(a.v * b.v); }
  friend Lane1 operator/(Lane1 a, Lane1 b) { return Lane1(a.v / b.v); }
  friend bool operator<(Lane1 a, Lane1 b) { return a.v < b.v; }
  friend bool operator>(Lane1 a, Lane1 b) { return a.v > b.v; }
  friend bool operator<=(Lane1 a, Lane1 b) { return a.v <= b.v; }
  // max/min as the AVX instructions define them (second operand on NaN).
  friend Lane1 max(Lane1 a, Lane1 b) { return Lane1(a.v > b.v ? a.v : b.v); }
  friend Lane1 abs(Lane1 a) {
    uint64_t u;
    std::memcpy(&u, &a.v, 8);
    u &= ~(uint64_t(1) << 63);
    std::memcpy(&a.v, &u, 8);
    return a;
  }
  friend Lane1 select(bool m, Lane1 a, Lane1 b) { return m ? a : b; }
  // Round to the nearest integer (ties to even) by the 1.5·2^52 trick, as
  // the vector version does.
  friend Lane1 round_int(Lane1 x) { return Lane1((x.v + 6755399441055744.0) - 6755399441055744.0); }
  friend Lane1 pow2_int(Lane1 n) {  // 2^n, n integral in [-1022, 1023]
    const uint64_t u = uint64_t(int64_t(n.v) + 1023) << 52;
    double d;
    std::memcpy(&d, &u, 8);
    return Lane1(d);
  }
  friend void split_exponent(Lane1 w, Lane1* e, Lane1* m) {
    uint64_t u;
    std::memcpy(&u, &w.v, 8);
    e->v = double(int64_t(u >> 52) - 1023);
    u = (u & ((uint64_t(1) << 52) - 1)) | (uint64_t(1023) << 52);
    std::memcpy(&m->v, &u, 8);
  }
};

}  // namespace zs::light
