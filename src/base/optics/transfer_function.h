// Transfer function: colour and opacity piecewise linear in the scalar,
// clamped outside their first/last points (scene spec). Both are merged onto
// one sorted breakpoint list so an integrator can walk the intervals on which
// colour and opacity are both linear.
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace zs {

struct ColorPoint {
  double s, r, g, b;
};
struct OpacityPoint {
  double s, a;
};

// Opacity is clamped to this so that extinction -ln(1-a) stays finite.
constexpr double kMaxOpacity = 1.0 - 1e-6;
// Distinct colour and opacity positions a transfer function may have.
constexpr int kMaxBreakpoints = 32000;

class TransferFunction {
 public:
  TransferFunction() = default;
  // Points must be strictly increasing in s (throws std::invalid_argument).
  TransferFunction(std::vector<ColorPoint> color, std::vector<OpacityPoint> opacity,
                   double unit_distance = 1.0);

  // Merged breakpoints: every colour and opacity s, sorted, unique. Between
  // breakpoints k and k+1 (and outside the ends) c and a are linear (const).
  const std::vector<double>& breakpoints() const { return bs_; }
  double unit_distance() const { return unit_; }

  // Colour and opacity at s with one search: {r, g, b, a}.
  std::array<double, 4> rgba(double s) const;
  // The same inside a known interval k (interval(s) == k); no search.
  std::array<double, 4> rgba_in(int k, double s) const;
  // Exact values at breakpoint k.
  const std::array<double, 4>& rgba_at_breakpoint(int k) const { return at_bs_[size_t(k)]; }
  std::array<double, 3> color(double s) const;
  double opacity(double s) const;  // clamped to [0, kMaxOpacity]
  // Extinction per unit length: -ln(1 - a(s)) / unit_distance.
  double extinction(double s) const;
  // Largest opacity over [lo, hi]; 0 means everything in the range is invisible.
  double max_opacity(double lo, double hi) const;
  // True when the opacity is exactly 0 on all of [lo, hi] (lo <= hi): one
  // search among the maximal closed runs where it is, for per-tet culling.
  bool transparent_over(double lo, double hi) const {
    // The first run ending at or after lo; it must also start at or before lo.
    const auto it = std::lower_bound(zero_end_.begin(), zero_end_.end(), lo);
    return it != zero_end_.end() && zero_begin_[size_t(it - zero_end_.begin())] <= lo && hi <= *it;
  }
  // 1 / (breakpoints[k+1] - breakpoints[k]), one per interval (batch kernels).
  const double* inverse_widths() const { return inv_width_.data(); }
  // Index k with breakpoints[k] <= s < breakpoints[k+1]; -1 below the first.
  int interval(double s) const;

  const std::vector<ColorPoint>& color_points() const { return color_; }
  const std::vector<OpacityPoint>& opacity_points() const { return opacity_; }

 private:
  std::vector<ColorPoint> color_;
  std::vector<OpacityPoint> opacity_;
  std::vector<double> bs_;
  std::vector<std::array<double, 4>> at_bs_;  // colour and opacity at each breakpoint
  std::vector<double> inv_width_;             // 1 / (bs_[k+1] - bs_[k])
  std::vector<double> zero_begin_, zero_end_; // maximal closed runs of zero opacity, sorted (±inf at the ends)
  double unit_ = 1.0;
};

// Inline: both run once or twice per segment.
inline std::array<double, 4> TransferFunction::rgba_in(int k, double s) const {
  if (k < 0) return at_bs_.front();
  if (size_t(k) + 1 >= bs_.size()) return at_bs_.back();
  const double t = (s - bs_[size_t(k)]) * inv_width_[size_t(k)];
  const auto &a = at_bs_[size_t(k)], &b = at_bs_[size_t(k) + 1];
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]), a[3] + t * (b[3] - a[3])};
}

inline int TransferFunction::interval(double s) const {
  // Transfer functions are short: counting the points at or below s beats a
  // binary search below a few dozen points, and has no branch that depends on
  // s (the scalars of consecutive segments are unrelated: mispredictions).
  const size_t n = bs_.size();
  if (n <= 16) {
    if (s != s) return int(n) - 1;  // NaN, as upper_bound would place it
    int k = -1;
    for (size_t j = 0; j < n; ++j) k += bs_[j] <= s;
    return k;
  }
  return int(std::upper_bound(bs_.begin(), bs_.end(), s) - bs_.begin()) - 1;
}

}  // namespace zs
