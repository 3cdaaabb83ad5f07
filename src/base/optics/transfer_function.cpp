#include "base/optics/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace zs {

namespace {

template <class P>
void check_sorted(const std::vector<P>& pts, const char* what) {
  if (pts.empty()) throw std::invalid_argument(std::string(what) + ": needs at least one point");
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!std::isfinite(pts[i].s))
      throw std::invalid_argument(std::string(what) + ": point " + std::to_string(i) + " has a non-finite scalar");
    if (i > 0 && !(pts[i].s > pts[i - 1].s))
      throw std::invalid_argument(std::string(what) + ": points must be strictly increasing in the scalar (point " +
                                  std::to_string(i) + " is " + (pts[i].s == pts[i - 1].s ? "a duplicate" : "out of order") +
                                  ")");
  }
}

// Linear interpolation of field F of a sorted point list, clamped at the ends.
template <class P, class F>
double lerp_points(const std::vector<P>& pts, double s, F field) {
  // Only a default-constructed function has no points; using one is a bug in
  // the caller (a fuzzing finding: it was undefined behaviour).
  if (pts.empty()) throw std::logic_error("transfer function used before it was given points");
  if (s <= pts.front().s) return field(pts.front());
  if (s >= pts.back().s) return field(pts.back());
  auto it = std::upper_bound(pts.begin(), pts.end(), s, [](double v, const P& p) { return v < p.s; });
  const P& hi = *it;
  const P& lo = *(it - 1);
  const double t = (s - lo.s) / (hi.s - lo.s);
  return field(lo) + t * (field(hi) - field(lo));
}

}  // namespace

TransferFunction::TransferFunction(std::vector<ColorPoint> color, std::vector<OpacityPoint> opacity,
                                   double unit_distance)
    : color_(std::move(color)), opacity_(std::move(opacity)), unit_(unit_distance) {
  check_sorted(color_, "transfer_function.color");
  check_sorted(opacity_, "transfer_function.opacity");
  if (!(unit_ > 0) || !std::isfinite(unit_))
    throw std::invalid_argument("transfer_function.unit_distance must be a positive number");
  for (auto& p : opacity_) {
    if (!(p.a >= 0 && p.a <= 1)) throw std::invalid_argument("transfer_function.opacity: values must be in [0, 1]");
    // Clamping the control points (not the interpolant) keeps a(s) linear
    // between breakpoints; it moves a(s) by at most 1e-6 where a > 1 - 1e-6.
    p.a = std::min(p.a, kMaxOpacity);
  }
  for (const auto& p : color_)
    if (!(p.r >= 0 && p.g >= 0 && p.b >= 0 && p.r <= 1 && p.g <= 1 && p.b <= 1))
      throw std::invalid_argument("transfer_function.color: values must be in [0, 1]");
  for (const auto& p : color_) bs_.push_back(p.s);
  for (const auto& p : opacity_) bs_.push_back(p.s);
  std::sort(bs_.begin(), bs_.end());
  bs_.erase(std::unique(bs_.begin(), bs_.end()), bs_.end());
  // The compositor keeps a pixel's current interval in 16 bits.
  if (bs_.size() > size_t(kMaxBreakpoints))
    throw std::invalid_argument("transfer_function: at most " + std::to_string(kMaxBreakpoints) +
                                " distinct colour and opacity points");
  // Both colour and opacity are linear between merged breakpoints, so their
  // values there define them everywhere.
  for (double b : bs_) {
    const auto c = this->color(b);  // the parameters shadow the members here
    at_bs_.push_back({c[0], c[1], c[2], this->opacity(b)});
  }
  for (size_t k = 0; k + 1 < bs_.size(); ++k) {
    inv_width_.push_back(1.0 / (bs_[k + 1] - bs_[k]));
    // Subnormal spacings overflow 1/width, and every lookup between them
    // would be NaN (found by fuzzing the default ramp over [0, 1e-308]).
    if (!std::isfinite(inv_width_.back())) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "transfer_function: points at s = %.17g and s = %.17g are too close together",
                    bs_[k], bs_[k + 1]);
      throw std::invalid_argument(msg);
    }
  }
  // Runs of zero opacity: opacity is linear between its points and constant
  // outside them, so it is 0 on [p_i, p_j] exactly when every point from i
  // to j is 0, below the first point when that one is, above the last likewise.
  const size_t n = opacity_.size();
  for (size_t i = 0; i < n;) {
    if (opacity_[i].a != 0) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j + 1 < n && opacity_[j + 1].a == 0) ++j;
    zero_begin_.push_back(i == 0 ? -INFINITY : opacity_[i].s);
    zero_end_.push_back(j + 1 == n ? INFINITY : opacity_[j].s);
    i = j + 1;
  }
}

std::array<double, 4> TransferFunction::rgba(double s) const { return rgba_in(interval(s), s); }

std::array<double, 3> TransferFunction::color(double s) const {
  return {lerp_points(color_, s, [](const ColorPoint& p) { return p.r; }),
          lerp_points(color_, s, [](const ColorPoint& p) { return p.g; }),
          lerp_points(color_, s, [](const ColorPoint& p) { return p.b; })};
}

double TransferFunction::opacity(double s) const {
  return lerp_points(opacity_, s, [](const OpacityPoint& p) { return p.a; });
}

double TransferFunction::extinction(double s) const { return -std::log1p(-opacity(s)) / unit_; }

double TransferFunction::max_opacity(double lo, double hi) const {
  if (lo > hi) std::swap(lo, hi);
  // Piecewise linear: the maximum is at an end or at an opacity point inside.
  double m = std::max(opacity(lo), opacity(hi));
  for (const auto& p : opacity_)
    if (p.s > lo && p.s < hi) m = std::max(m, p.a);
  return m;
}


}  // namespace zs
