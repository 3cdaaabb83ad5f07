#include "bench/line_plot.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "util/atomic_file.h"

namespace zs {

namespace {

constexpr const char* kFonts[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "DejaVuSans"};

std::string font() {
  for (const char* f : kFonts)
    if (std::filesystem::exists(f)) return f;
  return "";
}

std::string tick_label(double v) {
  char buf[32];
  if (v == std::floor(v) && v < 1e7) std::snprintf(buf, sizeof buf, "%.0f", v);  // image sizes
  else if (v >= 1e4 || (v > 0 && v < 1e-2)) std::snprintf(buf, sizeof buf, "%.0e", v);
  else std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

void write_line_plot(const std::string& path, const PlotSpec& spec, const std::vector<PlotSeries>& series) {
  namespace IBA = OIIO::ImageBufAlgo;
  const int W = spec.width, H = spec.height;
  const int left = 90, right = 210, top = 50, bottom = 70;
  OIIO::ImageBuf img(OIIO::ImageSpec(W, H, 3, OIIO::TypeDesc::UINT8));
  IBA::fill(img, {1.f, 1.f, 1.f});
  const std::string f = font();
  auto text = [&](int x, int y, const std::string& s, int size = 14) {
    IBA::render_text(img, x, y, s, size, f, {0.f, 0.f, 0.f});
  };

  // Data range (positive values only on log axes).
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& s : series)
    for (size_t k = 0; k < s.x.size(); ++k) {
      if ((spec.log_x && s.x[k] <= 0) || (spec.log_y && s.y[k] <= 0) || !std::isfinite(s.y[k])) continue;
      x0 = std::min(x0, s.x[k]), x1 = std::max(x1, s.x[k]);
      y0 = std::min(y0, s.y[k]), y1 = std::max(y1, s.y[k]);
    }
  if (!(x0 <= x1)) x0 = 1, x1 = 10;
  if (!(y0 <= y1)) y0 = 1, y1 = 10;
  auto tx = [&](double v) { return spec.log_x ? std::log10(v) : v; };
  auto ty = [&](double v) { return spec.log_y ? std::log10(v) : v; };
  double ax0 = tx(x0), ax1 = tx(x1), ay0 = ty(y0), ay1 = ty(y1);
  for (const auto& [v, label] : spec.y_marks)
    if (v > 0 || !spec.log_y) ay0 = std::min(ay0, ty(v)), ay1 = std::max(ay1, ty(v));
  if (spec.log_y) ay0 = std::floor(ay0), ay1 = std::ceil(ay1);
  if (spec.scatter && spec.log_x) ax0 = std::floor(ax0), ax1 = std::ceil(ax1);
  if (ax1 - ax0 < 1e-12) ax0 -= 0.5, ax1 += 0.5;
  if (ay1 - ay0 < 1e-12) ay0 -= 0.5, ay1 += 0.5;
  const double pad_x = 0.04 * (ax1 - ax0);
  ax0 -= pad_x, ax1 += pad_x;
  auto px = [&](double v) { return left + (tx(v) - ax0) / (ax1 - ax0) * (W - left - right); };
  auto py = [&](double v) { return H - bottom - (ty(v) - ay0) / (ay1 - ay0) * (H - top - bottom); };

  const float grey[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0.f, 0.f, 0.f};
  // Grid and ticks: x at the data's x values (resolutions), y per decade.
  std::vector<double> xt;
  for (const auto& s : series) xt.insert(xt.end(), s.x.begin(), s.x.end());
  std::sort(xt.begin(), xt.end());
  xt.erase(std::unique(xt.begin(), xt.end()), xt.end());
  if (spec.scatter) {
    xt.clear();
    if (spec.log_x)
      for (int e = int(std::lround(ax0 + pad_x)); e <= int(std::lround(ax1 - pad_x)); ++e) xt.push_back(std::pow(10.0, e));
    else
      for (int k = 0; k <= 5; ++k) xt.push_back(ax0 + pad_x + (ax1 - ax0 - 2 * pad_x) * k / 5);
  }
  for (double v : xt) {
    const int X = int(px(v));
    IBA::render_line(img, X, top, X, H - bottom, grey);
    text(X - 18, H - bottom + 20, tick_label(v), 12);
  }
  if (spec.log_y) {
    for (int e = int(ay0); e <= int(ay1); ++e) {
      const int Y = int(py(std::pow(10.0, e)));
      IBA::render_line(img, left, Y, W - right, Y, grey);
      text(10, Y + 5, tick_label(std::pow(10.0, e)), 12);
    }
  } else {
    for (int k = 0; k <= 5; ++k) {
      const double v = ay0 + (ay1 - ay0) * k / 5;
      const int Y = int(py(v));
      IBA::render_line(img, left, Y, W - right, Y, grey);
      text(10, Y + 5, tick_label(v), 12);
    }
  }
  for (const auto& [v, label] : spec.y_marks) {
    const int Y = int(py(v));
    for (int X = left; X < W - right; X += 12) IBA::render_line(img, X, Y, std::min(X + 6, W - right), Y, black);
    text(W - right - 8 * int(label.size()) - 4, Y - 4, label, 12);
  }
  IBA::render_box(img, left, top, W - right, H - bottom, black);
  text(left, 30, spec.title, 18);
  text(left + (W - left - right) / 2 - 60, H - 20, spec.xlabel + (spec.log_x ? " (log)" : ""));
  text(10, top - 12, spec.ylabel + (spec.log_y ? " (log)" : ""), 13);

  static const float palette[][3] = {{0.12f, 0.47f, 0.71f}, {0.84f, 0.15f, 0.16f}, {0.17f, 0.63f, 0.17f},
                                     {1.0f, 0.5f, 0.05f},   {0.58f, 0.4f, 0.74f},  {0.55f, 0.34f, 0.29f},
                                     {0.89f, 0.47f, 0.76f}, {0.5f, 0.5f, 0.5f}};
  for (size_t si = 0; si < series.size(); ++si) {
    const float* c = palette[si % 8];
    const auto& s = series[si];
    int prev_x = -1, prev_y = -1;
    for (size_t k = 0; k < s.x.size(); ++k) {
      if ((spec.log_x && s.x[k] <= 0) || (spec.log_y && s.y[k] <= 0) || !std::isfinite(s.y[k])) continue;
      const int X = int(px(s.x[k])), Y = int(py(s.y[k]));
      IBA::render_box(img, X - 3, Y - 3, X + 3, Y + 3, {c[0], c[1], c[2]}, true);
      if (k < s.labels.size() && !s.labels[k].empty())
        IBA::render_text(img, X + 6, Y + 4, s.labels[k], 10, f, {c[0], c[1], c[2]});
      if (prev_x >= 0 && !spec.scatter)
        for (int d = -1; d <= 1; ++d) IBA::render_line(img, prev_x, prev_y + d, X, Y + d, {c[0], c[1], c[2]});
      prev_x = X, prev_y = Y;
    }
    const int ly = top + 20 + int(si) * 22;
    IBA::render_box(img, W - right + 15, ly - 8, W - right + 35, ly - 2, {c[0], c[1], c[2]}, true);
    text(W - right + 42, ly, s.name, 13);
  }

  AtomicFile out(path);
  if (!img.write(out.temp_path())) throw std::runtime_error(path + ": cannot write plot: " + img.geterror());
  out.commit();
}

}  // namespace zs
