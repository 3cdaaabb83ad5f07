#include "bench/scan_bench.h"
#include "base/util/memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>

#include "bench/bench_inputs.h"
#include "geometry/tets/topology.h"
#include "raster/tile_sink.h"
#include "scene/scene.h"
#include "scene/scene_input.h"
#include "base/util/atomic_file.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {

namespace {

// Rotation (0, 0, 0) as in the seed: orthographic down -z, y up, the mesh's
// x/y extent filling the image with one common scale (B-Convert digest §3.1).
Camera seed_camera(const TetMesh& m, uint32_t w, uint32_t h) {
  const Bounds b = bounds_of(m);
  Camera c;
  c.projection = Projection::Orthographic;
  const glm::dvec3 mid = 0.5 * (b.lo + b.hi);
  const double ex = b.hi.x - b.lo.x, ey = b.hi.y - b.lo.y;
  c.height = 1.01 * std::max(ey, ex * double(h) / double(w));
  if (!(c.height > 0)) c.height = 1;
  c.target = mid;
  c.eye = {mid.x, mid.y, b.hi.z + 0.1 * std::max(b.diagonal(), 1e-300)};
  c.up = {0, 1, 0};
  return c;
}

// Every cell visible (opacity > 0 everywhere), so every face is projected as in the seed.
TransferFunction bench_tf(const TetMesh& m) {
  const TransferFunction d = default_transfer_function(m);
  const double lo = d.color_points().front().s, hi = d.color_points().back().s;
  return TransferFunction(d.color_points(), {{lo, 0.05}, {hi, 0.6}}, d.unit_distance());
}

// Compares tiles against a reference image without keeping a second one.
struct DiffSink : TileSink {
  const Image* ref = nullptr;
  Image* keep = nullptr;
  double max_diff = 0;
  void tile(const TileRect& t, const float* rgba) override {
    const size_t n = size_t(t.width()) * 4;
    for (uint32_t y = t.y0; y < t.y1; ++y, rgba += n) {
      if (ref) {
        const float* r = ref->at(t.x0, y);
        for (size_t k = 0; k < n; ++k) max_diff = std::max(max_diff, double(std::abs(rgba[k] - r[k])));
      }
      if (keep) std::copy(rgba, rgba + n, keep->at(t.x0, y));
    }
  }
};

}  // namespace

std::vector<ScanBenchRow> run_scan_bench(const ScanBenchOptions& opt) {
  check_volume_inputs(opt.inputs, "bench scan", false);  // all of them, before the first is measured
  const std::vector<std::string> names = bench_row_names(opt.inputs);
  std::vector<ScanBenchRow> rows;
  const uint64_t budget = frame_budget(opt.memory_budget_bytes);
  for (size_t i = 0; i < opt.inputs.size(); ++i) {
    const SceneInput in = load_scene_input(opt.inputs[i], {});
    const Scene& scene = in.scene;
    const TetMesh& mesh = in.mesh;
    const Topology topo = build_topology(mesh);
    const std::string& name = names[i];
    for (uint32_t size : opt.sizes) {
      RenderSettings rs = scene.settings;
      rs.width = rs.height = size;
      rs.threads = 1;
      rs.memory_budget_bytes = budget;
      rs.progress = false;
      rs.raster_only = size > opt.raster_only_above;
      rs.face_area_stats = true;
      rs.phase_times = true;  // the seed's tables split list generation from scan
      if (!scene.has_camera) rs.camera = seed_camera(mesh, size, size);
      if (!scene.has_transfer_function) rs.tf = bench_tf(mesh);
      // The bounding box first: the reference for missing pixels and images.
      const uint64_t img_bytes = uint64_t(size) * size * 16;
      const bool keep = img_bytes * 3 < budget && !rs.raster_only;
      Image ref;
      uint64_t ref_hits = 0;
      std::vector<std::pair<ScanStrategy, BConvertVariant>> runs{{ScanStrategy::BBox, BConvertVariant::Truncate}};
      for (ScanStrategy s : opt.strategies) {
        if (s == ScanStrategy::BBox) continue;
        if (s == ScanStrategy::BConvert)
          for (BConvertVariant v : opt.variants) runs.push_back({s, v});
        else
          runs.push_back({s, BConvertVariant::Truncate});
      }
      const bool bbox_wanted = std::count(opt.strategies.begin(), opt.strategies.end(), ScanStrategy::BBox) > 0;
      for (const auto& [strategy, variant] : runs) {
        rs.scan = strategy;
        rs.bconvert_variant = variant;
        ScanBenchRow row;
        row.mesh = name;
        row.size = size;
        row.strategy = to_string(strategy);
        row.variant = strategy == ScanStrategy::BConvert ? to_string(variant) : "-";
        for (int r = 0; r < std::max(1, opt.repeat); ++r) {
          RenderStats st;
          DiffSink sink;
          const bool is_ref = strategy == ScanStrategy::BBox;
          if (keep && is_ref && r == 0) {
            ref = Image(size, size);
            sink.keep = &ref;
          } else if (keep && !is_ref) {
            sink.ref = &ref;
          }
          NullSink null;
          TileSink& target = (sink.keep || sink.ref) ? static_cast<TileSink&>(sink) : static_cast<TileSink&>(null);
          render_zsweep_tiles(mesh, topo, rs, target, keep ? img_bytes * 2 : 0, &st);
          const double total = st.ms_list_generation + st.ms_scan_convert;
          if (r == 0 || total < row.total_ms) {
            row.list_generation_ms = st.ms_list_generation;
            row.scan_convert_ms = st.ms_scan_convert;
            row.total_ms = total;
          }
          row.render_ms = rs.raster_only ? -1 : r == 0 ? st.ms_total : std::min(row.render_ms, st.ms_total);
          row.pixel_tests = st.pixel_tests;
          row.pixel_hits = st.pixel_hits;
          row.pixel_misses = st.pixel_misses;
          row.rendered_pixels = st.rendered_pixels;
          row.faces_projected = st.faces_projected;
          row.bconvert_fallbacks = st.bconvert_fallbacks;
          row.face_to_bbox_area_ratio = st.bbox_area > 0 ? st.face_area / st.bbox_area : 0;
          row.mean_face_area_px = st.faces_projected ? st.face_area / double(st.faces_projected) : 0;
          for (int k = 0; k < 4; ++k) row.row_end_misses[k] = st.row_end_misses[k];
          if (keep) row.image_max_abs_diff = is_ref ? 0.0 : sink.max_diff;
        }
        if (strategy == ScanStrategy::BBox) ref_hits = row.pixel_hits;
        row.missing_pixels = ref_hits > row.pixel_hits ? ref_hits - row.pixel_hits : 0;
        if (strategy != ScanStrategy::BBox || bbox_wanted) rows.push_back(row);
        if (opt.progress)
          std::fprintf(stderr, "%s %u² %s%s%s: list %.1f ms, scan %.1f ms, render %.1f ms, hits %llu, missing %llu\n",
                       name.c_str(), size, row.strategy.c_str(), row.variant == "-" ? "" : "/",
                       row.variant == "-" ? "" : row.variant.c_str(), row.list_generation_ms, row.scan_convert_ms,
                       row.render_ms, (unsigned long long)row.pixel_hits, (unsigned long long)row.missing_pixels);
      }
    }
  }
  return rows;
}

void write_scan_bench_csv(const std::string& path, const std::vector<ScanBenchRow>& rows) {
  AtomicFile out(path);
  {
    std::ofstream f(out.temp_path());
    f << "mesh,size,strategy,variant,list_generation_ms,scan_convert_ms,total_ms,pixel_tests,pixel_hits,"
         "pixel_misses,missing_pixels,rendered_pixels,image_max_abs_diff,face_to_bbox_area_ratio,render_ms,"
         "mean_face_area_px,faces_projected,bconvert_fallbacks,row_end_0,row_end_1,row_end_2,row_end_3plus\n";
    for (const auto& r : rows) {
      char buf[1024];
      std::snprintf(buf, sizeof buf, "%s,%u,%s,%s,%.3f,%.3f,%.3f,%llu,%llu,%llu,%llu,%llu,%s,%.4f,%.3f,%.3f,%llu,%llu,%llu,%llu,%llu,%llu\n",
                    r.mesh.c_str(), r.size, r.strategy.c_str(), r.variant.c_str(), r.list_generation_ms,
                    r.scan_convert_ms, r.total_ms, (unsigned long long)r.pixel_tests,
                    (unsigned long long)r.pixel_hits, (unsigned long long)r.pixel_misses,
                    (unsigned long long)r.missing_pixels, (unsigned long long)r.rendered_pixels,
                    r.image_max_abs_diff < 0 ? "" : std::to_string(r.image_max_abs_diff).c_str(),
                    r.face_to_bbox_area_ratio, r.render_ms, r.mean_face_area_px,
                    (unsigned long long)r.faces_projected, (unsigned long long)r.bconvert_fallbacks,
                    (unsigned long long)r.row_end_misses[0], (unsigned long long)r.row_end_misses[1],
                    (unsigned long long)r.row_end_misses[2], (unsigned long long)r.row_end_misses[3]);
      f << buf;
    }
    if (!f) throw std::runtime_error(path + ": cannot write CSV");
  }
  out.commit();
}

std::vector<ScanBenchRow> read_scan_bench_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  std::vector<ScanBenchRow> rows;
  size_t line_no = 1;
  if (!std::getline(in, line) || line.rfind("mesh,size,strategy,variant,", 0) != 0)
    throw std::runtime_error(path + ":1: not a zsweep bench scan CSV");
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    std::vector<std::string> f;
    size_t start = 0;
    for (size_t k = 0; k <= line.size(); ++k)
      if (k == line.size() || line[k] == ',') f.push_back(line.substr(start, k - start)), start = k + 1;
    if (f.size() != 22) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": expected 22 columns");
    try {
      ScanBenchRow r;
      r.mesh = f[0];
      r.size = uint32_t(std::stoul(f[1]));
      r.strategy = f[2];
      r.variant = f[3];
      r.list_generation_ms = std::stod(f[4]);
      r.scan_convert_ms = std::stod(f[5]);
      r.total_ms = std::stod(f[6]);
      r.pixel_tests = std::stoull(f[7]);
      r.pixel_hits = std::stoull(f[8]);
      r.pixel_misses = std::stoull(f[9]);
      r.missing_pixels = std::stoull(f[10]);
      r.rendered_pixels = std::stoull(f[11]);
      r.image_max_abs_diff = f[12].empty() ? -1 : std::stod(f[12]);
      r.face_to_bbox_area_ratio = std::stod(f[13]);
      r.render_ms = std::stod(f[14]);
      r.mean_face_area_px = std::stod(f[15]);
      r.faces_projected = std::stoull(f[16]);
      r.bconvert_fallbacks = std::stoull(f[17]);
      for (int k = 0; k < 4; ++k) r.row_end_misses[k] = std::stoull(f[18 + size_t(k)]);
      rows.push_back(r);
    } catch (const std::logic_error&) {
      throw std::runtime_error(path + ":" + std::to_string(line_no) + ": not a number");
    }
  }
  return rows;
}

}  // namespace zs
