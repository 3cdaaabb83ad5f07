#include "bench/plot_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace zs {

namespace {

// "1.500" -> "1.5", "2.000" -> "2", "-0" -> "0", "2.50e-05" -> "2.5e-5", "3e+06" -> "3e6".
std::string trim_number(const std::string& s) {
  const size_t e = s.find('e');
  std::string m = s.substr(0, e), x = e == std::string::npos ? "" : s.substr(e + 1);
  if (m.find('.') != std::string::npos) {
    while (m.back() == '0') m.pop_back();
    if (m.back() == '.') m.pop_back();
  }
  if (m == "-0") m = "0";
  if (x.empty() || m == "0") return m;
  const bool neg = x[0] == '-';
  size_t k = (x[0] == '-' || x[0] == '+') ? 1 : 0;
  while (k + 1 < x.size() && x[k] == '0') ++k;
  return m + "e" + (neg ? "-" : "") + x.substr(k);
}

std::string format(double v, int decimals, bool exponent) {
  char buf[64];
  std::snprintf(buf, sizeof buf, exponent ? "%.*e" : "%.*f", decimals, v);
  return trim_number(buf);
}

TextBox at(const TextBox& ink, double x, double y) { return {x + ink.x0, y + ink.y0, x + ink.x1, y + ink.y1}; }

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> out;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return out;
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / mag;
  const double step = (r < 1.5 ? 1 : r < 3 ? 2 : r < 7 ? 5 : 10) * mag;
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
  for (double k = k0; k <= k1; ++k) out.push_back(k == 0 ? 0.0 : k * step);
  return out;
}

std::vector<std::string> tick_labels(const std::vector<double>& values) {
  if (values.empty()) return {};
  std::vector<double> s = values;
  std::sort(s.begin(), s.end());
  double gap = std::numeric_limits<double>::infinity(), big = 0;
  for (size_t k = 0; k < s.size(); ++k) {
    big = std::max(big, std::abs(s[k]));
    if (k && s[k] > s[k - 1]) gap = std::min(gap, s[k] - s[k - 1]);
  }
  if (!std::isfinite(gap)) gap = big > 0 ? big : 1;
  const bool exponent = big >= 1e6 || (big > 0 && big < 1e-3);
  std::vector<std::string> out(values.size());
  for (int d = 0; d <= 17; ++d) {
    bool ok = true;
    for (size_t k = 0; k < values.size() && ok; ++k) {
      out[k] = format(values[k], d, exponent);
      ok = std::abs(std::strtod(out[k].c_str(), nullptr) - values[k]) <= 0.01 * gap;
      for (size_t j = 0; j < k && ok; ++j) ok = (out[j] == out[k]) == (values[j] == values[k]);
    }
    if (ok) break;
  }
  return out;
}

std::string decade_label(int e) {
  if (e < -3 || e > 4) return "1e" + std::to_string(e);
  return format(std::pow(10.0, e), std::max(0, -e), false);
}

double PlotLayout::px(double v) const {
  const double t = log_x ? std::log10(v) : v;
  return left + (t - ax0) / (ax1 - ax0) * (right - left);
}

double PlotLayout::py(double v) const {
  const double t = log_y ? std::log10(v) : v;
  return bottom - (t - ay0) / (ay1 - ay0) * (bottom - top);
}

bool PlotLayout::drawable(double x, double y) const {
  return std::isfinite(x) && std::isfinite(y) && (!log_x || x > 0) && (!log_y || y > 0);
}

PlotLayout layout_plot(const PlotSpec& spec, const std::vector<PlotSeries>& series, const TextMeasure& measure) {
  PlotLayout L;
  L.width = spec.width, L.height = spec.height;
  L.log_x = spec.log_x, L.log_y = spec.log_y;
  const int W = spec.width, H = spec.height;

  // Axis ranges, in log10 units on log axes; decades on log axes.
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& s : series)
    for (size_t k = 0; k < s.x.size() && k < s.y.size(); ++k)
      if (L.drawable(s.x[k], s.y[k])) {
        x0 = std::min(x0, s.x[k]), x1 = std::max(x1, s.x[k]);
        y0 = std::min(y0, s.y[k]), y1 = std::max(y1, s.y[k]);
      }
  if (!(x0 <= x1)) x0 = 1, x1 = 10;
  if (!(y0 <= y1)) y0 = 1, y1 = 10;
  auto tx = [&](double v) { return L.log_x ? std::log10(v) : v; };
  auto ty = [&](double v) { return L.log_y ? std::log10(v) : v; };
  double ax0 = tx(x0), ax1 = tx(x1), ay0 = ty(y0), ay1 = ty(y1);
  for (const auto& [v, label] : spec.y_marks)
    if (v > 0 || !L.log_y) ay0 = std::min(ay0, ty(v)), ay1 = std::max(ay1, ty(v));
  // The tolerance keeps a value on a decade (1e-8) from adding a decade.
  if (L.log_y) ay0 = std::floor(ay0 + 1e-9), ay1 = std::ceil(ay1 - 1e-9);
  if (spec.scatter && L.log_x) ax0 = std::floor(ax0 + 1e-9), ax1 = std::ceil(ax1 - 1e-9);
  if (ax1 - ax0 < 1e-12) ax0 -= 0.5, ax1 += 0.5;
  if (ay1 - ay0 < 1e-12) ay0 -= 0.5, ay1 += 0.5;
  const double pad_x = 0.04 * (ax1 - ax0);
  ax0 -= pad_x, ax1 += pad_x;
  if (!L.log_y) {  // room for the points at the ends; the ticks stay round
    const double pad_y = 0.04 * (ay1 - ay0);
    ay0 -= pad_y, ay1 += pad_y;
  }
  L.ax0 = ax0, L.ax1 = ax1, L.ay0 = ay0, L.ay1 = ay1;

  // Ticks: decades on log axes, round values on linear ones, and the data's
  // x values (image sizes, thresholds) on line plots.
  std::vector<std::string> xl, yl;
  if (spec.scatter && L.log_x) {
    for (int e = int(std::ceil(ax0 - 1e-9)); e <= int(std::floor(ax1 + 1e-9)); ++e)
      L.xticks.push_back(std::pow(10.0, e)), xl.push_back(decade_label(e));
  } else if (spec.scatter) {
    L.xticks = nice_ticks(ax0, ax1), xl = tick_labels(L.xticks);
  } else {
    for (const auto& s : series)
      for (size_t k = 0; k < s.x.size() && k < s.y.size(); ++k)
        if (L.drawable(s.x[k], s.y[k])) L.xticks.push_back(s.x[k]);
    std::sort(L.xticks.begin(), L.xticks.end());
    L.xticks.erase(std::unique(L.xticks.begin(), L.xticks.end()), L.xticks.end());
    xl = tick_labels(L.xticks);
  }
  if (L.log_y) {
    for (int e = int(std::ceil(ay0 - 1e-9)); e <= int(std::floor(ay1 + 1e-9)); ++e)
      L.yticks.push_back(std::pow(10.0, e)), yl.push_back(decade_label(e));
  } else {
    L.yticks = nice_ticks(ay0, ay1), yl = tick_labels(L.yticks);
  }

  // Margins: the y tick labels on the left, the legend on the right.
  constexpr int kTick = 12, kLegend = 13, kPoint = 10, kPointGap = 3;
  double yl_width = 0, legend_width = 0;
  for (const auto& s : yl) yl_width = std::max(yl_width, measure(s, kTick).x1);
  for (const auto& s : series) legend_width = std::max(legend_width, measure(s.name, kLegend).x1);
  L.left = std::max(70, int(std::ceil(yl_width)) + 20);
  L.right = W - std::max(210, int(std::ceil(legend_width)) + 52);
  L.top = 64;
  L.bottom = H - 70;

  std::vector<TextBox> taken;
  // `gap`: pixels kept clear around the box, so that neighbours do not read
  // as one word.
  auto free = [&](const TextBox& b, double gap) {
    if (b.x0 < 0 || b.y0 < 0 || b.x1 > W || b.y1 > H) return false;
    const TextBox g{b.x0 - gap, b.y0 - gap, b.x1 + gap, b.y1 + gap};
    for (const TextBox& t : taken)
      if (g.overlaps(t)) return false;
    return true;
  };
  // Positions are whole pixels, as they are drawn; `force` places even over
  // something (the title, axis labels and legend come first and always fit).
  auto place = [&](const std::string& s, int size, double x, double y, TextRole role, int si, bool force) {
    PlotText t;
    t.text = s, t.size = size, t.role = role, t.series = si;
    t.x = std::round(x), t.y = std::round(y);
    t.box = at(measure(s, size), t.x, t.y);
    if (!force && !free(t.box, role == TextRole::Point ? kPointGap : 0)) return false;
    taken.push_back(t.box);
    L.texts.push_back(t);
    return true;
  };

  place(spec.title, 18, L.left, 26, TextRole::Title, -1, true);
  place(spec.ylabel + (L.log_y ? " (log)" : ""), 13, 10, L.top - 14, TextRole::AxisLabel, -1, true);
  {
    const std::string s = spec.xlabel + (L.log_x ? " (log)" : "");
    const TextBox e = measure(s, 14);
    place(s, 14, (L.left + L.right) / 2.0 - (e.x0 + e.x1) / 2, H - 20, TextRole::AxisLabel, -1, true);
  }
  for (size_t si = 0; si < series.size(); ++si)
    place(series[si].name, kLegend, L.right + 42, L.top + 20 + int(si) * 22, TextRole::Legend, int(si), true);
  // Reference marks: right-aligned above their line, else below it.
  for (const auto& [v, label] : spec.y_marks) {
    if (L.log_y && v <= 0) continue;
    const TextBox e = measure(label, kTick);
    const double Y = L.py(v);
    if (!place(label, kTick, L.right - 4 - e.x1, Y - 4, TextRole::Mark, -1, false))
      place(label, kTick, L.right - 4 - e.x1, Y + 4 - e.y0, TextRole::Mark, -1, false);
  }
  // X tick labels centred under their ticks, one baseline for all; a label
  // that would touch its neighbour (3 px apart) is left out.
  double ascent = 0;
  for (const auto& s : xl) ascent = std::max(ascent, -measure(s, kTick).y0);
  TextBox last{-1e9, 0, -1e9, 0};
  for (size_t k = 0; k < L.xticks.size(); ++k) {
    const TextBox e = measure(xl[k], kTick);
    const double x = L.px(L.xticks[k]) - (e.x0 + e.x1) / 2, y = L.bottom + 8 + ascent;
    const TextBox b = at(e, std::round(x), std::round(y));
    if (b.x0 < last.x1 + 3) continue;
    if (place(xl[k], kTick, x, y, TextRole::XTick, -1, false)) last = b;
  }
  // Y tick labels right-aligned left of the axis, centred on their ticks.
  last = {0, 1e9, 0, 1e9};
  for (size_t k = 0; k < L.yticks.size(); ++k) {  // bottom up
    const TextBox e = measure(yl[k], kTick);
    const double x = L.left - 8 - e.x1, y = L.py(L.yticks[k]) - (e.y0 + e.y1) / 2;
    const TextBox b = at(e, std::round(x), std::round(y));
    if (b.y1 > last.y0 - 2) continue;
    if (place(yl[k], kTick, x, y, TextRole::YTick, -1, false)) last = b;
  }

  // Point labels: beside their point (right, then left), else the nearest
  // free place above or below with a leader line; never over another label
  // or a marker, always inside the plot.
  for (const auto& s : series)
    for (size_t k = 0; k < s.x.size() && k < s.y.size(); ++k)
      if (L.drawable(s.x[k], s.y[k])) {
        const double X = std::round(L.px(s.x[k])), Y = std::round(L.py(s.y[k]));
        taken.push_back({X - 3, Y - 3, X + 4, Y + 4});
      }
  const TextBox inside{double(L.left + 1), double(L.top + 1), double(L.right), double(L.bottom)};
  for (size_t si = 0; si < series.size(); ++si) {
    const PlotSeries& s = series[si];
    for (size_t k = 0; k < s.x.size() && k < s.y.size() && k < s.labels.size(); ++k) {
      if (s.labels[k].empty() || !L.drawable(s.x[k], s.y[k])) continue;
      const double X = std::round(L.px(s.x[k])), Y = std::round(L.py(s.y[k]));
      const TextBox e = measure(s.labels[k], kPoint);
      const double w = e.x1 - e.x0, h = e.y1 - e.y0, step = h + kPointGap + 1;
      bool placed = false;
      for (int ring = 0; !placed && ring * step <= L.bottom - L.top; ++ring)
        for (int sign : {-1, 1}) {
          if (placed || (ring == 0 && sign > 0)) continue;
          for (int side = 0; side < 2 && !placed; ++side) {
            const double bx0 = side == 0 ? X + 4 + kPointGap : X - 3 - kPointGap - w, by0 = Y + sign * ring * step - h / 2;
            const double x = std::round(bx0 - e.x0), y = std::round(by0 - e.y0);
            const TextBox b = at(e, x, y);
            if (b.x0 < inside.x0 || b.y0 < inside.y0 || b.x1 > inside.x1 || b.y1 > inside.y1) continue;
            if (!place(s.labels[k], kPoint, x, y, TextRole::Point, int(si), false)) continue;
            PlotText& t = L.texts.back();
            t.leader = ring > 0, t.px = X, t.py = Y;
            placed = true;
          }
        }
      if (!placed) ++L.point_labels_dropped;
    }
  }
  return L;
}

}  // namespace zs
