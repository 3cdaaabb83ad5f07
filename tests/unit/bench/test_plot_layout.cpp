// The benchmark plots' layout (src/bench/plot_layout.h): round ticks with the
// fewest digits, x labels centred under their points, and no two labels
// overlapping, with a fixed-width stand-in font and with the real one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "bench/line_plot.h"
#include "bench/plot_layout.h"
#include "output/image_io.h"
#include "support/test_paths.h"

namespace zs {
namespace {

// A fixed-width font: 0.6 em per character, ascent 0.75 em, descent 0.2 em.
TextBox mono(const std::string& s, int size) { return {0, -0.75 * size, 0.6 * size * double(s.size()), 0.2 * size}; }

std::vector<std::string> texts_of(const PlotLayout& L, TextRole role) {
  std::vector<std::string> out;
  for (const PlotText& t : L.texts)
    if (t.role == role) out.push_back(t.text);
  return out;
}

void expect_no_overlaps(const PlotLayout& L) {
  for (size_t i = 0; i < L.texts.size(); ++i) {
    const TextBox& a = L.texts[i].box;
    EXPECT_GE(a.x0, 0) << L.texts[i].text;
    EXPECT_GE(a.y0, 0) << L.texts[i].text;
    EXPECT_LE(a.x1, L.width) << L.texts[i].text;
    EXPECT_LE(a.y1, L.height) << L.texts[i].text;
    // Point labels keep 3 px from everything, so neighbours do not read as one.
    const double g = L.texts[i].role == TextRole::Point ? 2.9 : 0;
    const TextBox grown{a.x0 - g, a.y0 - g, a.x1 + g, a.y1 + g};
    for (size_t j = 0; j < i; ++j)
      EXPECT_FALSE(grown.overlaps(L.texts[j].box)) << "'" << L.texts[i].text << "' at '" << L.texts[j].text << "'";
  }
}

// The early-termination figure: thresholds 0..16, errors 2e-5..8.00002 levels
// (the data whose y ticks read 1.60002, 3.20002, ...).
std::vector<PlotSeries> et_series() {
  return {{"measured", {0, 1, 2, 4, 8, 16}, {2e-5, 0.3, 0.72, 1.6, 3.4, 6.6}, {}},
          {"bound t/2 + err(t=0)", {1, 2, 4, 8, 16}, {0.50002, 1.00002, 2.00002, 4.00002, 8.00002}, {}}};
}

PlotSpec et_spec() {
  PlotSpec s;
  s.title = "default 64x64: early-termination error vs its bound";
  s.xlabel = "threshold t (levels)";
  s.ylabel = "max abs error, 8-bit levels";
  s.log_x = s.log_y = false;
  return s;
}

// `bench accuracy default --sizes 64`: 26 settings, several at one place.
std::vector<PlotSeries> accuracy_series() {
  struct R {
    const char *group, *setting;
    double ms, err;
  };
  const R rows[] = {
      {"integrator", "exact", 12.079, 8.9407e-08},      {"integrator", "exact-single", 3.663, 2.38419e-07},
      {"integrator", "linear", 8.783, 0.0127137},       {"integrator", "preintegrated", 104.456, 0.0129324},
      {"integrator", "taylor2", 11.557, 0.0255666},     {"scan", "bbox", 3.963, 8.9407e-08},
      {"scan", "span", 11.968, 8.9407e-08},             {"scan", "bconvert-truncate", 4.716, 0.820587},
      {"scan", "bconvert-round", 17.392, 0.316897},     {"scan", "bconvert-dilate", 5.491, 0.818463},
      {"scan", "bconvert-dda3d", 14.010, 8.9407e-08},   {"scan", "bconvert-runlength", 13.048, 0.820587},
      {"early-termination", "t=0", 7.365, 8.9407e-08},  {"early-termination", "t=1", 9.054, 0.00113016},
      {"early-termination", "t=2", 8.843, 0.00283527},  {"early-termination", "t=4", 14.066, 0.00621533},
      {"early-termination", "t=8", 9.122, 0.0133458},   {"early-termination", "t=16", 8.193, 0.0260312},
      {"max-list", "max-list=0", 12.021, 8.9407e-08},   {"max-list", "max-list=256", 3.863, 8.9407e-08},
      {"max-list", "max-list=64", 7.872, 8.9407e-08},   {"max-list", "max-list=16", 7.932, 8.9407e-08},
      {"max-list", "max-list=4", 7.872, 8.9407e-08},    {"resolution", "8-upsampled", 0.770, 0.313498},
      {"resolution", "16-upsampled", 5.281, 0.159846},  {"resolution", "32-upsampled", 2.174, 0.041971}};
  std::vector<PlotSeries> out;
  for (const R& r : rows) {
    if (out.empty() || out.back().name != r.group) out.push_back({r.group, {}, {}, {}});
    out.back().x.push_back(r.ms), out.back().y.push_back(r.err), out.back().labels.push_back(r.setting);
  }
  return out;
}

PlotSpec accuracy_spec() {
  PlotSpec s;
  s.title = "default 64x64: time vs max abs error against the reference";
  s.xlabel = "render time, ms";
  s.ylabel = "max abs error (exact 0 drawn at 1e-8)";
  s.scatter = true;
  s.y_marks = {{1.0 / 255.0, "1/255"}};
  return s;
}

TEST(PlotLayout, NiceTicksAreRound) {
  EXPECT_EQ(nice_ticks(-0.32, 8.32), (std::vector<double>{0, 2, 4, 6, 8}));
  EXPECT_EQ(nice_ticks(-0.64, 16.64), (std::vector<double>{0, 5, 10, 15}));
  EXPECT_EQ(tick_labels(nice_ticks(0.3, 1.7)), (std::vector<std::string>{"0.4", "0.6", "0.8", "1", "1.2", "1.4", "1.6"}));
  EXPECT_EQ(tick_labels(nice_ticks(-1.1, 1.1)), (std::vector<std::string>{"-1", "-0.5", "0", "0.5", "1"}));
  EXPECT_EQ(tick_labels(nice_ticks(1e-5, 9e-5)), (std::vector<std::string>{"2e-5", "4e-5", "6e-5", "8e-5"}));
  EXPECT_TRUE(nice_ticks(1, 1).empty());
}

TEST(PlotLayout, TickLabelsUseTheFewestDigits) {
  EXPECT_EQ(tick_labels({0, 0.5, 1, 1.5}), (std::vector<std::string>{"0", "0.5", "1", "1.5"}));
  EXPECT_EQ(tick_labels({0.1 + 0.2, 0.6}), (std::vector<std::string>{"0.3", "0.6"}));
  EXPECT_EQ(tick_labels({512, 1024, 2048}), (std::vector<std::string>{"512", "1024", "2048"}));
  EXPECT_EQ(tick_labels({1e6, 2e6, 3e6}), (std::vector<std::string>{"1e6", "2e6", "3e6"}));
  EXPECT_EQ(tick_labels({-0.0}), (std::vector<std::string>{"0"}));
  // Data values (not round) keep the digits that tell them apart.
  EXPECT_EQ(tick_labels({1.0, 1.25, 2.0}), (std::vector<std::string>{"1", "1.25", "2"}));
  EXPECT_EQ(decade_label(-8), "1e-8");
  EXPECT_EQ(decade_label(-3), "0.001");
  EXPECT_EQ(decade_label(0), "1");
  EXPECT_EQ(decade_label(4), "10000");
  EXPECT_EQ(decade_label(5), "1e5");
}

TEST(PlotLayout, LinearAxesGetRoundTicksAndCentredLabels) {
  const PlotLayout L = layout_plot(et_spec(), et_series(), mono);
  EXPECT_EQ(texts_of(L, TextRole::YTick), (std::vector<std::string>{"0", "2", "4", "6", "8"}));
  EXPECT_EQ(texts_of(L, TextRole::XTick), (std::vector<std::string>{"0", "1", "2", "4", "8", "16"}));
  for (const PlotText& t : L.texts) {
    if (t.role == TextRole::XTick) {  // under its point, within the rounding to whole pixels
      const double v = std::stod(t.text);
      EXPECT_NEAR(0.5 * (t.box.x0 + t.box.x1), L.px(v), 1.0) << t.text;
      EXPECT_GT(t.box.y0, L.bottom) << t.text;
    }
    if (t.role == TextRole::YTick) {  // beside its tick, left of the axis
      EXPECT_NEAR(0.5 * (t.box.y0 + t.box.y1), L.py(std::stod(t.text)), 1.0) << t.text;
      EXPECT_LT(t.box.x1, L.left) << t.text;
    }
  }
  expect_no_overlaps(L);
}

TEST(PlotLayout, CrowdedTickLabelsAreThinnedNotOverlapped) {
  PlotSpec s = et_spec();
  s.title = "t";
  s.width = 460;  // 0..16 over 180 px: "0", "0.5" and "1" cannot all fit
  const std::vector<PlotSeries> series{{"measured", {0, 0.5, 1, 2, 4, 8, 16}, {0, 0.1, 0.3, 0.7, 1.6, 3.4, 6.6}, {}}};
  const PlotLayout L = layout_plot(s, series, mono);
  const auto x = texts_of(L, TextRole::XTick);
  EXPECT_LT(x.size(), 7u);
  EXPECT_EQ(x.front(), "0");
  EXPECT_EQ(x.back(), "16");
  expect_no_overlaps(L);
}

TEST(PlotLayout, ScatterLabelsDoNotOverlap) {
  for (const TextMeasure& m : {TextMeasure(mono), plot_text_measure()}) {
    const PlotLayout L = layout_plot(accuracy_spec(), accuracy_series(), m);
    EXPECT_EQ(L.point_labels_dropped, 0u);
    EXPECT_EQ(texts_of(L, TextRole::Point).size(), 26u);
    EXPECT_EQ(texts_of(L, TextRole::YTick),
              (std::vector<std::string>{"1e-8", "1e-7", "1e-6", "1e-5", "1e-4", "0.001", "0.01", "0.1", "1"}));
    EXPECT_EQ(texts_of(L, TextRole::XTick), (std::vector<std::string>{"0.1", "1", "10", "100", "1000"}));
    expect_no_overlaps(L);
    for (const PlotText& t : L.texts)
      if (t.role == TextRole::Point) {  // inside the plot; beside the point unless a leader says where
        EXPECT_GT(t.box.x0, L.left);
        EXPECT_LE(t.box.x1, L.right);
        EXPECT_GT(t.box.y0, L.top);
        EXPECT_LE(t.box.y1, L.bottom);
        if (!t.leader) EXPECT_NEAR(0.5 * (t.box.y0 + t.box.y1), t.py, 1.0) << t.text;
      }
  }
}

TEST(PlotLayout, ManyPointsInOnePlaceStillNeverOverlap) {
  std::vector<PlotSeries> s{{"all", {}, {}, {}}};
  for (int k = 0; k < 60; ++k)
    s[0].x.push_back(10 + 0.01 * k), s[0].y.push_back(1e-4), s[0].labels.push_back("setting-" + std::to_string(k));
  const PlotLayout L = layout_plot(accuracy_spec(), s, plot_text_measure());
  EXPECT_EQ(texts_of(L, TextRole::Point).size() + L.point_labels_dropped, 60u);
  expect_no_overlaps(L);
}

// End to end through the drawing: the ink of each x tick label sits centred
// on its grid line (it sat 18 px, 0.4 threshold units, to the left).
TEST(PlotLayout, DrawnXLabelsSitUnderTheirGridLines) {
  const auto path = (test::scratch_dir() / "et.png").string();
  write_line_plot(path, et_spec(), et_series());
  const Image img = read_image(path);
  auto dark = [&](uint32_t x, uint32_t y) { return img.at(x, y)[0] < 0.5f; };
  auto grey = [&](uint32_t x, uint32_t y) {
    const float v = img.at(x, y)[0];
    return v > 0.8f && v < 0.9f && std::abs(img.at(x, y)[2] - v) < 0.01f;
  };
  // Grid columns: a row inside the plot (left of the legend, whose
  // anti-aliased text has grey too) with only a few grey pixels.
  std::vector<uint32_t> grid;
  for (uint32_t y = 100; y < 400 && grid.empty(); ++y) {
    std::vector<uint32_t> g;
    for (uint32_t x = 60; x < img.width - 210; ++x)
      if (grey(x, y)) g.push_back(x);
    if (g.size() >= 6 && g.size() <= 12) grid = g;
  }
  ASSERT_EQ(grid.size(), 6u);
  // Ink below the axis (y 534..556, right of the y tick labels), split into
  // labels at gaps over 4 px.
  std::vector<std::pair<uint32_t, uint32_t>> runs;
  for (uint32_t x = 60; x < img.width; ++x) {
    bool ink = false;
    for (uint32_t y = 534; y < 557 && !ink; ++y) ink = dark(x, y);
    if (!ink) continue;
    if (!runs.empty() && x - runs.back().second <= 4) runs.back().second = x;
    else runs.push_back({x, x});
  }
  ASSERT_EQ(runs.size(), grid.size());
  for (size_t k = 0; k < grid.size(); ++k)
    EXPECT_NEAR(0.5 * (runs[k].first + runs[k].second), double(grid[k]), 2.0) << "label " << k;
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

}  // namespace
}  // namespace zs
