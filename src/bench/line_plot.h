// Small PNG line plots for benchmark figures (log or linear axes, legend),
// drawn with OpenImageIO's line and text rendering (DejaVu Sans).
#pragma once

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

// Throws std::runtime_error naming the file when it cannot be written.
void write_line_plot(const std::string& path, const PlotSpec& spec, const std::vector<PlotSeries>& series);

}  // namespace zs
