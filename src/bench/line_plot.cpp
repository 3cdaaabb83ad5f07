#include "bench/line_plot.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "base/util/atomic_file.h"

namespace zs {

namespace {

constexpr const char* kFonts[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "DejaVuSans"};

const std::string& font() {
  static const std::string f = [] {
    for (const char* p : kFonts)
      if (std::filesystem::exists(p)) return std::string(p);
    return std::string();
  }();
  return f;
}

}  // namespace

TextMeasure plot_text_measure() {
  return [](const std::string& text, int size) {
    const OIIO::ROI r = OIIO::ImageBufAlgo::text_size(text, size, font());
    if (!r.defined()) return TextBox{0, -0.8 * size, 0.6 * size * double(text.size()), 0.25 * size};
    return TextBox{double(r.xbegin), double(r.ybegin), double(r.xend), double(r.yend)};
  };
}

void write_line_plot(const std::string& path, const PlotSpec& spec, const std::vector<PlotSeries>& series) {
  namespace IBA = OIIO::ImageBufAlgo;
  const PlotLayout L = layout_plot(spec, series, plot_text_measure());
  OIIO::ImageBuf img(OIIO::ImageSpec(L.width, L.height, 3, OIIO::TypeDesc::UINT8));
  IBA::fill(img, {1.f, 1.f, 1.f});
  const float grey[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0.f, 0.f, 0.f};
  for (double v : L.xticks) {
    const int X = int(std::lround(L.px(v)));
    IBA::render_line(img, X, L.top, X, L.bottom, grey);
  }
  for (double v : L.yticks) {
    const int Y = int(std::lround(L.py(v)));
    IBA::render_line(img, L.left, Y, L.right, Y, grey);
  }
  for (const auto& [v, label] : spec.y_marks) {
    if (L.log_y && v <= 0) continue;
    const int Y = int(std::lround(L.py(v)));
    for (int X = L.left; X < L.right; X += 12) IBA::render_line(img, X, Y, std::min(X + 6, L.right), Y, black);
  }
  IBA::render_box(img, L.left, L.top, L.right, L.bottom, black);

  static const float palette[][3] = {{0.12f, 0.47f, 0.71f}, {0.84f, 0.15f, 0.16f}, {0.17f, 0.63f, 0.17f},
                                     {1.0f, 0.5f, 0.05f},   {0.58f, 0.4f, 0.74f},  {0.55f, 0.34f, 0.29f},
                                     {0.89f, 0.47f, 0.76f}, {0.5f, 0.5f, 0.5f}};
  auto colour = [&](int si) { return OIIO::cspan<float>(palette[size_t(si) % 8], 3); };
  for (size_t si = 0; si < series.size(); ++si) {
    const auto& s = series[si];
    int prev_x = -1, prev_y = -1;
    for (size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      if (!L.drawable(s.x[k], s.y[k])) continue;
      const int X = int(std::lround(L.px(s.x[k]))), Y = int(std::lround(L.py(s.y[k])));
      IBA::render_box(img, X - 3, Y - 3, X + 3, Y + 3, colour(int(si)), true);
      if (prev_x >= 0 && !spec.scatter)
        for (int d = -1; d <= 1; ++d) IBA::render_line(img, prev_x, prev_y + d, X, Y + d, colour(int(si)));
      prev_x = X, prev_y = Y;
    }
  }
  for (const PlotText& t : L.texts) {
    const bool coloured = t.role == TextRole::Point;
    if (t.role == TextRole::Legend)  // the swatch left of the name
      IBA::render_box(img, int(t.x) - 27, int(t.y) - 8, int(t.x) - 7, int(t.y) - 2, colour(t.series), true);
    if (t.leader) {  // from the point to the near end of the label, mid-height
      const double ex = t.px < t.box.x0 ? t.box.x0 - 1 : t.box.x1 + 1, ey = 0.5 * (t.box.y0 + t.box.y1);
      IBA::render_line(img, int(t.px), int(t.py), int(std::lround(ex)), int(std::lround(ey)), colour(t.series));
    }
    IBA::render_text(img, int(t.x), int(t.y), t.text, t.size, font(),
                     coloured ? colour(t.series) : OIIO::cspan<float>(black, 3));
  }

  AtomicFile out(path);
  if (!img.write(out.temp_path())) throw std::runtime_error(path + ": cannot write plot: " + img.geterror());
  out.commit();
}

}  // namespace zs
