#include "base/optics/segment_integrator.h"

#include <algorithm>
#include <cmath>

#include "base/optics/light_kernel.h"

namespace zs {

namespace {

constexpr int kPsiN = 512;

// Mean of ln(w) over [w0, w1] = (G(w1) - G(w0)) / (w1 - w0), G = w ln w - w,
// from the logs of the ends. Where the divided difference would cancel, the
// series in q = (w1 - w0)/(w1 + w0): mean = (L0 + L1)/2 + q²/3 + q⁴/5 + q⁶/7
// + ... (that is (L0 + L1)/2 + atanh(q)/q - 1), truncated at q⁸/9 < 1e-17.
double mean_log(double w0, double L0, double w1, double L1) {
  const double d = w1 - w0, q = d / (w0 + w1);
  if (std::abs(q) < 1e-2) {
    const double q2 = q * q;
    return 0.5 * (L0 + L1) + q2 * (1.0 / 3 + q2 * (1.0 / 5 + q2 * (1.0 / 7)));
  }
  return (w1 * L1 - w0 * L0) / d - 1.0;
}
double mean_log(double w0, double w1) { return mean_log(w0, std::log(w0), w1, std::log(w1)); }

// Optical depth from 0 to t of a piece where w = 1 - a goes linearly from w0
// (at 0) to w1 (at len): -t · mean(ln w over [w0, w(t)]) / unit.
struct PieceDepth {
  double w0, dw_dt, inv_unit;
  double operator()(double t) const { return -t * mean_log(w0, w0 + dw_dt * t) * inv_unit; }
};

// Gauss–Legendre 8-point nodes/weights on [-1, 1].
constexpr double kGx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kGw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

template <class F>
double gl8(const F& f, double a, double b) {
  const double h = 0.5 * (b - a), m = 0.5 * (a + b);
  double s = 0;
  for (int i = 0; i < 4; ++i) s += kGw[i] * (f(m - h * kGx[i]) + f(m + h * kGx[i]));
  return s * h;
}

// Gauss–Legendre 4-point: the cheap half of an embedded error estimate.
constexpr double kG4x[2] = {0.3399810435848563, 0.8611363115940526};
constexpr double kG4w[2] = {0.6521451548625461, 0.3478548451374538};

template <class F>
double gl4(const F& f, double a, double b) {
  const double h = 0.5 * (b - a), m = 0.5 * (a + b);
  double s = 0;
  for (int i = 0; i < 2; ++i) s += kG4w[i] * (f(m - h * kG4x[i]) + f(m + h * kG4x[i]));
  return s * h;
}

// Adaptive: accept when one panel and its two halves agree to `tol`.
template <class F>
double adaptive_gl(const F& f, double a, double b, double whole, double tol, int depth) {
  const double m = 0.5 * (a + b);
  const double l = gl8(f, a, m), r = gl8(f, m, b);
  // !(> tol) also stops on NaN, which no amount of splitting would fix.
  if (depth <= 0 || !(std::abs(l + r - whole) > tol)) return l + r;
  return adaptive_gl(f, a, m, l, 0.5 * tol, depth - 1) + adaptive_gl(f, m, b, r, 0.5 * tol, depth - 1);
}

}  // namespace

const char* to_string(Integrator i) {
  switch (i) {
    case Integrator::Exact: return "exact";
    case Integrator::Linear: return "linear";
    case Integrator::Preintegrated: return "preintegrated";
    case Integrator::Taylor2: return "taylor2";
  }
  return "?";
}

bool parse_integrator(const std::string& s, Integrator* out) {
  for (Integrator i : {Integrator::Exact, Integrator::Linear, Integrator::Preintegrated, Integrator::Taylor2})
    if (s == to_string(i)) return *out = i, true;
  return false;
}

SegmentLight integrate_linear_piece(const double c0[3], double a0, const double c1[3], double a1, double len,
                                    double unit) {
  return integrate_linear_piece(c0, a0, std::log(1.0 - a0), c1, a1, std::log(1.0 - a1), len, unit);
}

SegmentLight integrate_linear_piece(const double c0[3], double a0, double L0, const double c1[3], double a1,
                                    double L1, double len, double unit) {
  SegmentLight out{{0, 0, 0}, 1.0};
  if (!(len > 0)) return out;
  const double w0 = 1.0 - a0, w1 = 1.0 - a1;
  double T, Jm;  // transmittance over the piece, and the mean of T(t) over it
  const bool varying_colour = c0[0] != c1[0] || c0[1] != c1[1] || c0[2] != c1[2];
  if (w0 == w1) {
    const double tau = -L0 / unit;
    if (tau == 0) return out;
    T = std::exp(-tau * len);
    Jm = varying_colour ? -std::expm1(-tau * len) / (tau * len) : 0.0;
  } else {
    const double kappa = len / unit;
    T = std::exp(kappa * mean_log(w0, L0, w1, L1));
    Jm = 0;
    if (varying_colour) {
      // The mean of T only enters as (c1 - c0)·mean. On x = t/len in [0, 1],
      // f = T(x) = exp(-D(x)) with D' = g = -kappa·ln w(x); g, g', g'' are
      // known at both ends, so f to f''' are too, and the two-point Hermite
      // rule (exact for degree 7)
      //   ∫f ≈ (f0 + f1)/2 + 3(f0' - f1')/28 + (f0'' + f1'')/84 + (f0''' - f1''')/1680
      // costs no further exp or log. Its error is f⁽⁸⁾(ξ)/25401600, and
      // |f⁽⁸⁾| ≤ Y8(a, b, b·r, 2b·r², ..., 720b·r⁶) (complete Bell
      // polynomial, f ≤ 1) with a = max g, r = |dw|/min w, b = kappa·r
      // bounding |g⁽ᵏ⁾| ≤ (k-1)!·b·r^(k-1). Where that bound times |c1 - c0|
      // exceeds 1e-9, Gauss–Legendre on T(t) instead. (light_kernel.h is
      // the same rule, four pieces at a time.)
      const double g0 = -kappa * L0, g1 = -kappa * L1;
      const double inv_w0 = 1.0 / w0, inv_w1 = 1.0 / w1, d = w1 - w0;
      const double A = std::max(g0, g1), r = std::abs(d) * std::max(inv_w0, inv_w1), B = kappa * r;
      const double dc = std::max({std::abs(c1[0] - c0[0]), std::abs(c1[1] - c0[1]), std::abs(c1[2] - c0[2])});
      using light::Lane1;
      if (dc * light::hermite8_bound(Lane1(A), Lane1(B), Lane1(r)).v <= light::kHermite8Tolerance) {
        const double h0 = d * inv_w0, h1 = d * inv_w1;  // dw/w: g' = -kappa·h, g'' = kappa·h²
        Jm = light::hermite8_mean(Lane1(g0), Lane1(g1), Lane1(kappa * h0), Lane1(kappa * h1), Lane1(kappa * h0 * h0),
                                  Lane1(kappa * h1 * h1), Lane1(T))
                 .v;
      } else {
        const PieceDepth depth{w0, d / len, 1.0 / unit};
        auto trans = [&](double t) { return std::exp(-depth(t)); };
        const double tol = 1e-8 * len;
        const double g8 = gl8(trans, 0.0, len);
        Jm = (std::abs(g8 - gl4(trans, 0.0, len)) <= tol ? g8 : adaptive_gl(trans, 0.0, len, g8, tol, 20)) / len;
      }
    }
  }
  // I = ∫ c τ T dt = [-c T] + c' ∫ T dt  (integration by parts, c linear).
  for (int k = 0; k < 3; ++k) out.rgb[k] = c0[k] - c1[k] * T + (c1[k] - c0[k]) * Jm;
  out.T = T;
  return out;
}

SegmentIntegrator::SegmentIntegrator(const TransferFunction& tf, Integrator kind) : tf_(tf), kind_(kind) {
  for (size_t k = 0; k < tf_.breakpoints().size(); ++k)
    L_at_bs_.push_back(std::log(1.0 - tf_.rgba_at_breakpoint(int(k))[3]));
  if (kind_ != Integrator::Preintegrated) return;
  // psi(tf·D, tb·D) = (1/D) ∫_0^D exp(-Φ(t)) dt for tau linear from tf to tb,
  // tabulated over gamma = x/(1+x) (x = tau·D), as Moreland and Angel (2004).
  psi_.resize(size_t(kPsiN) * kPsiN);
  for (int i = 0; i < kPsiN; ++i)
    for (int j = 0; j < kPsiN; ++j) {
      const double gf = std::min(double(i) / (kPsiN - 1), 0.9999), gb = std::min(double(j) / (kPsiN - 1), 0.9999);
      const double xf = gf / (1 - gf), xb = gb / (1 - gb);
      auto trans = [&](double t) { return std::exp(-(xf * t + 0.5 * (xb - xf) * t * t)); };
      psi_[size_t(i) * kPsiN + j] = float(adaptive_gl(trans, 0.0, 1.0, gl8(trans, 0.0, 1.0), 1e-9, 12));
    }
}

SegmentEnd SegmentIntegrator::end(double s) const {
  if (kind_ != Integrator::Exact) return {};
  const int k = tf_.interval(s);
  return {k, std::log(1.0 - tf_.rgba_in(k, s)[3])};
}

SegmentLight SegmentIntegrator::integrate(double s0, const SegmentEnd& e0, double s1, const SegmentEnd& e1,
                                          double L) const {
  if (!(L > 0)) return {{0, 0, 0}, 1.0};
  switch (kind_) {
    case Integrator::Exact: return exact(s0, e0, s1, e1, L);
    case Integrator::Linear: return linear(s0, s1, L);
    case Integrator::Preintegrated: return preintegrated(s0, s1, L);
    case Integrator::Taylor2: return taylor2(s0, s1, L);
  }
  return {{0, 0, 0}, 1.0};
}

SegmentLight SegmentIntegrator::linear(double s0, double s1, double L) const {
  const auto a = tf_.rgba(s0), b = tf_.rgba(s1);
  return integrate_linear_piece(a.data(), a[3], b.data(), b[3], L, tf_.unit_distance());
}

SegmentLight SegmentIntegrator::exact(double s0, const SegmentEnd& e0, double s1, const SegmentEnd& e1,
                                      double L) const {
  const int k0 = e0.k, k1 = e1.k;
  const double unit = tf_.unit_distance();
  if (k0 == k1) {
    // Within one interval colour and opacity are linear along the segment
    // (the common case): one piece.
    const auto a = tf_.rgba_in(k0, s0), b = tf_.rgba_in(k0, s1);
    return integrate_linear_piece(a.data(), a[3], e0.L, b.data(), b[3], e1.L, L, unit);
  }
  // Split where the scalar crosses breakpoints, in the order the ray meets them.
  const auto& bs = tf_.breakpoints();
  SegmentLight acc{{0, 0, 0}, 1.0};
  double t_prev = 0.0, L_prev = e0.L;
  std::array<double, 4> v_prev = tf_.rgba_in(k0, s0);
  auto add_piece = [&](double t_next, const std::array<double, 4>& v_next, double L_next) {
    const SegmentLight p = integrate_linear_piece(v_prev.data(), v_prev[3], L_prev, v_next.data(), v_next[3], L_next,
                                                  (t_next - t_prev) * L, unit);
    for (int k = 0; k < 3; ++k) acc.rgb[k] += acc.T * p.rgb[k];
    acc.T *= p.T;
    t_prev = t_next;
    v_prev = v_next;
    L_prev = L_next;
  };
  const double inv = 1.0 / (s1 - s0);
  if (k1 > k0) {
    for (int k = k0 + 1; k <= k1; ++k)
      add_piece((bs[size_t(k)] - s0) * inv, tf_.rgba_at_breakpoint(k), L_at_bs_[size_t(k)]);
  } else {
    // Decreasing scalar: cross breakpoints k0, k0-1, ..., k1+1.
    for (int k = k0; k > k1; --k)
      add_piece((bs[size_t(k)] - s0) * inv, tf_.rgba_at_breakpoint(k), L_at_bs_[size_t(k)]);
  }
  add_piece(1.0, tf_.rgba_in(k1, s1), e1.L);
  return acc;
}

SegmentLight SegmentIntegrator::preintegrated(double s0, double s1, double L) const {
  const double tf = tf_.extinction(s0), tb = tf_.extinction(s1);
  const double xf = tf * L, xb = tb * L;
  const double gf = xf / (1 + xf), gb = xb / (1 + xb);
  // Bilinear lookup of psi.
  const double fi = gf * (kPsiN - 1), fj = gb * (kPsiN - 1);
  const int i = std::min(int(fi), kPsiN - 2), j = std::min(int(fj), kPsiN - 2);
  const double u = fi - i, v = fj - j;
  auto at = [&](int a, int b) { return double(psi_[size_t(a) * kPsiN + b]); };
  const double psi = (1 - u) * ((1 - v) * at(i, j) + v * at(i, j + 1)) + u * ((1 - v) * at(i + 1, j) + v * at(i + 1, j + 1));
  const double T = std::exp(-0.5 * (xf + xb));
  const auto cf = tf_.color(s0), cb = tf_.color(s1);
  SegmentLight out;
  // C = C_b (psi - zeta) + C_f (1 - psi)   (Moreland & Angel 2004, Eq. 8)
  for (int k = 0; k < 3; ++k) out.rgb[k] = cb[k] * (psi - T) + cf[k] * (1 - psi);
  out.T = T;
  return out;
}

SegmentLight SegmentIntegrator::taylor2(double s0, double s1, double L) const {
  // The cheap compositing of the original ZSweep lineage: mean extinction and
  // mean colour over the segment, and T = e^-x replaced by 1 - x + x^2/2.
  // The series is only meaningful for thin segments; x is capped at 1 (where
  // it has its minimum, T = 1/2) so thick segments lose opacity instead of
  // gaining light — the error this costs is measured by `bench accuracy`.
  const auto a = tf_.rgba(s0), b = tf_.rgba(s1);
  const double tau = 0.5 * (-std::log(1.0 - a[3]) - std::log(1.0 - b[3])) / tf_.unit_distance();
  const double x = std::min(tau * L, 1.0);
  const double T = 1.0 - x + 0.5 * x * x;
  SegmentLight out;
  for (int k = 0; k < 3; ++k) out.rgb[k] = 0.5 * (a[k] + b[k]) * (1.0 - T);
  out.T = T;
  return out;
}

}  // namespace zs
