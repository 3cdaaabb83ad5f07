#include "bench/accuracy_bench.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "bench/bench_inputs.h"
#include "bench/line_plot.h"
#include "output/image_compare.h"
#include "geometry/tets/topology.h"
#include "render/reference/reference_renderer.h"
#include "scene/scene_input.h"
#include "base/util/atomic_file.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {

namespace {

// Bilinear resampling to the compared size: what a user gets by previewing
// at a lower resolution and looking at it full size.
Image upsample(const Image& src, uint32_t w, uint32_t h) {
  OIIO::ImageBuf in(OIIO::ImageSpec(int(src.width), int(src.height), 4, OIIO::TypeDesc::FLOAT),
                    const_cast<float*>(src.rgba.data()));
  Image out(w, h);
  OIIO::ImageBuf dst(OIIO::ImageSpec(int(w), int(h), 4, OIIO::TypeDesc::FLOAT), out.rgba.data());
  if (!OIIO::ImageBufAlgo::resample(dst, in, true)) throw std::runtime_error("resample: " + dst.geterror());
  return out;
}

struct Setting {
  std::string group, name;
  RenderSettings rs;
  double bound_levels = -1;  // early termination: t/2 levels on top of the t = 0 error
};

std::vector<Setting> settings_for(const RenderSettings& base, const std::vector<std::string>& groups) {
  auto has = [&](const char* g) { return std::find(groups.begin(), groups.end(), g) != groups.end(); };
  std::vector<Setting> out;
  RenderSettings b = base;
  b.scan = ScanStrategy::Span;
  b.integrator = Integrator::Exact;
  b.early_termination = 0;
  b.max_list_length = 0;
  if (has("integrator"))
    for (Integrator i : {Integrator::Exact, Integrator::Linear, Integrator::Preintegrated, Integrator::Taylor2}) {
      Setting s{"integrator", to_string(i), b};
      s.rs.integrator = i;
      out.push_back(s);
      if (i == Integrator::Exact) {  // the same in single precision
        Setting f{"integrator", "exact-single", b};
        f.rs.single_precision = true;
        out.push_back(f);
      }
    }
  if (has("scan")) {
    for (ScanStrategy k : {ScanStrategy::BBox, ScanStrategy::Span}) {
      Setting s{"scan", to_string(k), b};
      s.rs.scan = k;
      out.push_back(s);
    }
    for (BConvertVariant v : {BConvertVariant::Truncate, BConvertVariant::Round, BConvertVariant::Dilate,
                              BConvertVariant::Dda3d, BConvertVariant::RunLength}) {
      Setting s{"scan", std::string("bconvert-") + to_string(v), b};
      s.rs.scan = ScanStrategy::BConvert;
      s.rs.bconvert_variant = v;
      out.push_back(s);
    }
  }
  if (has("early-termination"))
    for (double t : {0.0, 1.0, 2.0, 4.0, 8.0, 16.0}) {
      Setting s{"early-termination", "t=" + std::to_string(int(t)), b};
      s.rs.early_termination = t;
      s.bound_levels = t / 2;
      out.push_back(s);
    }
  if (has("max-list"))
    for (uint32_t n : {0u, 256u, 64u, 16u, 4u}) {
      Setting s{"max-list", "max-list=" + std::to_string(n), b};
      s.rs.max_list_length = n;
      out.push_back(s);
    }
  return out;
}

}  // namespace

std::vector<AccuracyRow> run_accuracy_bench(const AccuracyBenchOptions& opt) {
  using Clock = std::chrono::steady_clock;
  auto ms_since = [](Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
  };
  check_volume_inputs(opt.inputs, "bench accuracy", true);  // all of them, before the first is measured
  const std::vector<std::string> names = bench_row_names(opt.inputs);
  std::vector<AccuracyRow> rows;
  for (size_t i = 0; i < opt.inputs.size(); ++i) {
    const std::string& input = opt.inputs[i];
    SceneInput base = load_scene_input(input == "default" ? "" : input, {});
    const Topology topo = build_topology(base.mesh);
    const std::string& name = names[i];
    for (uint32_t size : opt.sizes) {
      SceneInput in = base;  // the automatic camera depends on the size
      in.scene.settings.width = in.scene.settings.height = size;
      in.scene.settings.threads = opt.threads;
      in.scene.settings.progress = false;
      finish_scene(in);
      const RenderSettings& rs0 = in.scene.settings;
      ReferenceStats rstats;
      const auto tr = Clock::now();
      const Image ref = render_reference(in.mesh, topo, rs0, rs0.tf, &rstats);
      const double ref_ms = ms_since(tr);
      std::fprintf(stderr, "%s %u²: reference %.0f ms (%llu lost walks)\n", name.c_str(), size, ref_ms,
                   (unsigned long long)rstats.lost_walks);

      auto run = [&](const std::string& group, const std::string& setting, const RenderSettings& rs,
                     double bound) {
        AccuracyRow row{name, group, setting, size, rs.width};
        Image img;
        row.ms = INFINITY;
        for (int r = 0; r < opt.repeat; ++r) {
          RenderStats st;
          const auto t0 = Clock::now();
          img = render_zsweep(in.mesh, topo, rs, &st);
          row.ms = std::min(row.ms, ms_since(t0));
          row.fragments = st.fragments;
          row.early_terminated_pixels = st.early_terminated_pixels;
        }
        if (img.width != size) img = upsample(img, size, size);
        const ImageDiff d = compare_images(img, ref);
        row.reference_ms = ref_ms;
        row.max_abs = d.max_abs;
        row.rmse = d.rmse;
        row.psnr = d.psnr;
        row.pixels_over_1_255 = d.pixels_over_1_255;
        row.bound = bound;
        std::fprintf(stderr, "  %-18s %-22s %9.1f ms  max abs %.3g  rmse %.3g  >1/255: %llu\n", group.c_str(),
                     setting.c_str(), row.ms, row.max_abs, row.rmse, (unsigned long long)row.pixels_over_1_255);
        rows.push_back(row);
        return row;
      };

      const std::vector<Setting> settings = settings_for(rs0, opt.groups);
      if (!settings.empty()) {  // warm caches and clocks before the first timed run
        RenderStats st;
        render_zsweep(in.mesh, topo, settings.front().rs, &st);
      }
      double base_err = -1;
      for (const Setting& s : settings) {
        double bound = -1;
        if (s.bound_levels >= 0 && base_err >= 0) bound = base_err + s.bound_levels / 255.0;
        const AccuracyRow r = run(s.group, s.name, s.rs, bound);
        if (s.group == "early-termination" && s.bound_levels == 0) base_err = r.max_abs;
      }
      if (std::find(opt.groups.begin(), opt.groups.end(), "resolution") != opt.groups.end())
        for (uint32_t div : {8u, 4u, 2u}) {
          if (size / div < 8) continue;
          RenderSettings rs = rs0;
          rs.scan = ScanStrategy::Span;
          rs.width = rs.height = size / div;
          run("resolution", std::to_string(size / div) + "-upsampled", rs, -1);
        }
    }
  }
  return rows;
}

void write_accuracy_csv(const std::string& path, const std::vector<AccuracyRow>& rows) {
  AtomicFile out(path);
  {
    std::ofstream f(out.temp_path());
    f << "scene,size,group,setting,render_size,ms,reference_ms,max_abs,max_abs_levels,rmse,psnr,"
         "pixels_over_1_255,fragments,early_terminated_pixels,bound,within_bound\n";
    for (const auto& r : rows) {
      char buf[1024];
      std::snprintf(buf, sizeof buf, "%s,%u,%s,%s,%u,%.3f,%.3f,%.6g,%.4f,%.6g,%.3f,%llu,%llu,%llu,%s,%s\n",
                    r.scene.c_str(), r.size, r.group.c_str(), r.setting.c_str(), r.render_size, r.ms,
                    r.reference_ms, r.max_abs, r.max_abs * 255.0, r.rmse, std::isinf(r.psnr) ? 999.0 : r.psnr,
                    (unsigned long long)r.pixels_over_1_255, (unsigned long long)r.fragments,
                    (unsigned long long)r.early_terminated_pixels,
                    r.bound < 0 ? "" : std::to_string(r.bound).c_str(),
                    r.bound < 0 ? "" : (r.max_abs <= r.bound ? "yes" : "no"));
      f << buf;
    }
    if (!f) throw std::runtime_error(path + ": cannot write CSV");
  }
  out.commit();
}

void write_accuracy_plots(const std::string& dir, const std::vector<AccuracyRow>& rows) {
  std::filesystem::create_directories(dir);
  // Errors of exactly 0 (and float rounding) are drawn at this floor.
  constexpr double kFloor = 1e-8;
  std::map<std::pair<std::string, uint32_t>, std::vector<const AccuracyRow*>> by_case;
  for (const auto& r : rows) by_case[{r.scene, r.size}].push_back(&r);
  for (const auto& [key, rs] : by_case) {
    const std::string tag = key.first + "-" + std::to_string(key.second);
    for (int metric = 0; metric < 2; ++metric) {
      std::vector<PlotSeries> series;
      std::map<std::string, size_t> index;
      for (const AccuracyRow* r : rs) {
        if (!index.count(r->group)) index[r->group] = series.size(), series.push_back({r->group, {}, {}, {}});
        PlotSeries& s = series[index[r->group]];
        s.x.push_back(r->ms);
        s.y.push_back(std::max(metric == 0 ? r->max_abs : r->rmse, kFloor));
        s.labels.push_back(r->setting);
      }
      const char* what = metric == 0 ? "max abs error" : "RMSE";
      PlotSpec spec;
      spec.title = key.first + " " + std::to_string(key.second) + "x" + std::to_string(key.second) + ": time vs " +
                   what + " against the reference";
      spec.xlabel = "render time, ms";
      spec.ylabel = std::string(what) + " (exact 0 drawn at 1e-8)";
      spec.scatter = true;
      spec.y_marks = {{1.0 / 255.0, "1/255"}};
      write_line_plot(dir + (metric == 0 ? "/accuracy-" : "/accuracy-rmse-") + tag + ".png", spec, series);
    }

    PlotSeries measured{"measured", {}, {}, {}}, bound{"bound t/2 + err(t=0)", {}, {}, {}};
    for (const AccuracyRow* r : rs) {
      if (r->group != "early-termination") continue;
      const double t = std::stod(r->setting.substr(2));
      measured.x.push_back(t), measured.y.push_back(r->max_abs * 255.0);
      if (r->bound >= 0) bound.x.push_back(t), bound.y.push_back(r->bound * 255.0);
    }
    if (!measured.x.empty()) {
      PlotSpec es;
      es.title = key.first + " " + std::to_string(key.second) + "x" + std::to_string(key.second) + ": early-termination error vs its bound";
      es.xlabel = "threshold t (levels)";
      es.ylabel = "max abs error, 8-bit levels";
      es.log_x = es.log_y = false;
      write_line_plot(dir + "/et-bound-" + tag + ".png", es, {measured, bound});
    }
  }
}

}  // namespace zs
