// Small PNG line plots for benchmark figures (log or linear axes, legend),
// drawn with OpenImageIO's line and text rendering (DejaVu Sans) from the
// layout in plot_layout.h.
#pragma once

#include <string>
#include <vector>

#include "bench/plot_layout.h"

namespace zs {

// The font the plots are drawn in, measured as OpenImageIO draws it.
TextMeasure plot_text_measure();

// Throws std::runtime_error naming the file when it cannot be written.
void write_line_plot(const std::string& path, const PlotSpec& spec, const std::vector<PlotSeries>& series);

}  // namespace zs
