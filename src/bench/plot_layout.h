// Where everything in a benchmark plot goes, apart from drawing it: axis
// ranges, round tick values and their labels, and a place for every piece of
// text (title, axis labels, ticks, reference marks, legend, point labels) such
// that no two overlap. Pure geometry, so it is tested without a font
// (tests/unit/bench/test_plot_layout.cpp); line_plot.cpp draws it.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace zs {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  std::vector<std::string> labels;  // optional, one per point, drawn beside it
};

struct PlotSpec {
  std::string title, xlabel, ylabel;
  bool log_x = true, log_y = true;
  int width = 900, height = 600;
  // Scatter: markers only, no lines, x ticks per decade (log) instead of at
  // the data's x values.
  bool scatter = false;
  // Horizontal reference lines (e.g. the 1/255 threshold), labelled.
  std::vector<std::pair<double, std::string>> y_marks;
};

// Image pixels, y down; half-open, so boxes that only touch do not overlap.
struct TextBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool overlaps(const TextBox& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// The ink of `text` at `size` pixels relative to the left end of its
// baseline (y up from the baseline is negative), as the font draws it.
using TextMeasure = std::function<TextBox(const std::string& text, int size)>;

// Round values in [lo, hi]: multiples of 1, 2 or 5 times a power of ten,
// about `target` of them (at least two when the range allows).
std::vector<double> nice_ticks(double lo, double hi, int target = 5);
// One label per value with the fewest decimals (trailing zeros dropped) that
// tell the values apart and show each within 1 % of the gap between them;
// exponent form ("2e-5", "3e6") for magnitudes below 1e-3 or from 1e6.
std::vector<std::string> tick_labels(const std::vector<double>& values);
// 10^e: "0.001" ... "10000" written out, "1e-8" or "1e5" beyond.
std::string decade_label(int e);

enum class TextRole { Title, AxisLabel, XTick, YTick, Mark, Legend, Point };

struct PlotText {
  std::string text;
  int size = 12;
  double x = 0, y = 0;  // left end of the baseline
  TextBox box;          // the ink, where it lands
  TextRole role = TextRole::Title;
  int series = -1;  // Legend and Point: whose colour
  // Point labels moved away from their point get a line back to it.
  bool leader = false;
  double px = 0, py = 0;
};

struct PlotLayout {
  int width = 0, height = 0;
  int left = 0, right = 0, top = 0, bottom = 0;  // plot area: [left, right] x [top, bottom] in pixels
  double ax0 = 0, ax1 = 1, ay0 = 0, ay1 = 1;     // axis ranges (log10 of the data on log axes)
  bool log_x = true, log_y = true;
  std::vector<double> xticks, yticks;  // data units; grid lines (labels may be thinned out)
  std::vector<PlotText> texts;
  size_t point_labels_dropped = 0;  // no free place found anywhere near their point

  double px(double v) const;  // data -> pixel
  double py(double v) const;
  bool drawable(double x, double y) const;  // finite, and positive on a log axis
};

PlotLayout layout_plot(const PlotSpec& spec, const std::vector<PlotSeries>& series, const TextMeasure& measure);

}  // namespace zs
