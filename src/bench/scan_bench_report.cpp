// Tables mirroring the seed's Tables 4.2-4.10 and Figures 4.1-4.7 (time vs
// resolution per mesh) from the benchmark rows.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bench/line_plot.h"
#include "bench/scan_bench.h"
#include "base/util/atomic_file.h"

namespace zs {

namespace {

using Key = std::pair<std::string, uint32_t>;  // mesh, size

std::string label(const ScanBenchRow& r) { return r.variant == "-" ? r.strategy : r.strategy + "/" + r.variant; }

std::string fmt(double v, const char* f = "%.1f") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string thousands(uint64_t v) {
  std::string s = std::to_string(v);
  for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
  return s;
}

struct Index {
  std::vector<std::string> meshes;  // in input order
  std::vector<uint32_t> sizes;
  std::map<std::string, std::map<Key, const ScanBenchRow*>> by_label;
  explicit Index(const std::vector<ScanBenchRow>& rows) {
    std::set<uint32_t> sz;
    for (const auto& r : rows) {
      if (std::find(meshes.begin(), meshes.end(), r.mesh) == meshes.end()) meshes.push_back(r.mesh);
      sz.insert(r.size);
      by_label[label(r)][{r.mesh, r.size}] = &r;
    }
    sizes.assign(sz.begin(), sz.end());
  }
  const ScanBenchRow* at(const std::string& l, const std::string& m, uint32_t s) const {
    auto it = by_label.find(l);
    if (it == by_label.end()) return nullptr;
    auto jt = it->second.find({m, s});
    return jt == it->second.end() ? nullptr : jt->second;
  }
};

// A mesh x size table of f(row) for one strategy label (empty cells: not run).
template <class F>
void table(std::ostream& o, const Index& ix, const std::string& title, const std::string& l, F f) {
  o << "\n" << title << "\n\n| mesh |";
  for (uint32_t s : ix.sizes) o << " " << s << "² |";
  o << "\n| --- |";
  for (size_t k = 0; k < ix.sizes.size(); ++k) o << " ---: |";
  o << "\n";
  for (const auto& m : ix.meshes) {
    o << "| " << m << " |";
    for (uint32_t s : ix.sizes) {
      const ScanBenchRow* r = ix.at(l, m, s);
      o << " " << (r ? f(*r, s) : std::string("–")) << " |";
    }
    o << "\n";
  }
}

}  // namespace

void write_scan_bench_report(const std::string& dir, const std::vector<ScanBenchRow>& rows) {
  if (rows.empty()) return;
  std::filesystem::create_directories(dir);
  const Index ix(rows);
  const std::string bc = ix.by_label.count("bconvert/truncate") ? "bconvert/truncate" : "";
  std::string md;
  {
    std::ostringstream o;
    o << "# Scan-convert benchmark tables\n\nAll times in ms, one thread, whole ZSweep renders. `list` = per-face "
         "set-up (B-Convert: edge and compact lists), `scan` = the pixel loop.\n";
    table(o, ix, "**Table 4.2 analogue: bounding-box scan time (list + scan).**", "bbox",
          [](const ScanBenchRow& r, uint32_t) { return fmt(r.total_ms); });
    if (!bc.empty()) {
      table(o, ix, "**Table 4.3 analogue: B-Convert (truncate) time including list generation.**", bc,
            [](const ScanBenchRow& r, uint32_t) { return fmt(r.total_ms); });
      table(o, ix, "**Table 4.5 analogue: B-Convert scan-only time as % of the bounding box's scan-only time.**", bc,
            [&](const ScanBenchRow& r, uint32_t s) {
              const ScanBenchRow* b = ix.at("bbox", r.mesh, s);
              return b && b->scan_convert_ms > 0 ? fmt(100 * r.scan_convert_ms / b->scan_convert_ms, "%.1f%%") : "–";
            });
      table(o, ix, "**Table 4.6 analogue: share of B-Convert's time spent generating the lists.**", bc,
            [](const ScanBenchRow& r, uint32_t) {
              return r.total_ms > 0 ? fmt(100 * r.list_generation_ms / r.total_ms, "%.1f%%") : "–";
            });
      table(o, ix, "**Table 4.7 analogue: whole render time, B-Convert as % of bounding box.**", bc,
            [&](const ScanBenchRow& r, uint32_t s) {
              const ScanBenchRow* b = ix.at("bbox", r.mesh, s);
              return b && b->render_ms > 0 && r.render_ms > 0 ? fmt(100 * r.render_ms / b->render_ms, "%.1f%%") : "–";
            });
    }
    if (ix.by_label.count("span")) {
      table(o, ix, "**Span: time (list + scan) as % of the bounding box's (below 100% = faster).**", "span",
            [&](const ScanBenchRow& r, uint32_t s) {
              const ScanBenchRow* b = ix.at("bbox", r.mesh, s);
              return b && b->total_ms > 0 ? fmt(100 * r.total_ms / b->total_ms, "%.1f%%") : "–";
            });
      table(o, ix, "**Span vs bounding box: hits equal, max image difference.**", "span",
            [&](const ScanBenchRow& r, uint32_t s) {
              const ScanBenchRow* b = ix.at("bbox", r.mesh, s);
              std::string hits = b && b->pixel_hits == r.pixel_hits ? "equal" : "DIFFERENT";
              return hits + (r.image_max_abs_diff < 0 ? "" : ", " + fmt(r.image_max_abs_diff, "%g"));
            });
    }
    table(o, ix, "**Table 4.4 analogue: mean face area / mean bounding-box area (mean face area in pixels).**", "bbox",
          [](const ScanBenchRow& r, uint32_t) {
            return fmt(r.face_to_bbox_area_ratio, "%.2f") + " (" + fmt(r.mean_face_area_px, "%.1f") + ")";
          });
    // Tables 4.8 / 4.9: hits and misses at 2048² (or the largest size below).
    uint32_t hs = ix.sizes.front();
    for (uint32_t s : ix.sizes)
      if (s <= 2048) hs = s;
    o << "\n**Tables 4.8/4.9 analogue at " << hs << "²: hits (intercepta), misses (não intercepta), hits/misses, "
         "rendered pixels, missing hits (ausente) vs bounding box.**\n\n"
         "| mesh | strategy | hits | misses | hits/misses | rendered pixels | missing hits |\n"
         "| --- | --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& m : ix.meshes)
      for (const auto& [l, map] : ix.by_label) {
        const ScanBenchRow* r = ix.at(l, m, hs);
        if (!r) continue;
        o << "| " << m << " | " << l << " | " << thousands(r->pixel_hits) << " | " << thousands(r->pixel_misses)
          << " | " << (r->pixel_misses ? fmt(100.0 * double(r->pixel_hits) / double(r->pixel_misses), "%.1f%%") : "∞")
          << " | " << thousands(r->rendered_pixels) << " | " << thousands(r->missing_pixels) << " ("
          << fmt(r->pixel_hits + r->missing_pixels ? 100.0 * double(r->missing_pixels) / double(r->pixel_hits + r->missing_pixels) : 0,
                 "%.2f%%")
          << ") |\n";
      }
    // Missing hits per variant and size.
    o << "\n**Missing hits (ausente) as % of the bounding box's hits, per B-Convert variant.**\n\n| mesh | variant |";
    for (uint32_t s : ix.sizes) o << " " << s << "² |";
    o << "\n| --- | --- |";
    for (size_t k = 0; k < ix.sizes.size(); ++k) o << " ---: |";
    o << "\n";
    for (const auto& m : ix.meshes)
      for (const auto& [l, map] : ix.by_label) {
        if (l.rfind("bconvert/", 0) != 0) continue;
        o << "| " << m << " | " << l.substr(9) << " |";
        for (uint32_t s : ix.sizes) {
          const ScanBenchRow* r = ix.at(l, m, s);
          o << " "
            << (r ? fmt(100.0 * double(r->missing_pixels) / double(std::max<uint64_t>(1, r->pixel_hits + r->missing_pixels)), "%.3f%%") +
                        " (" + thousands(r->missing_pixels) + ")"
                  : "–")
            << " |";
        }
        o << "\n";
      }
    if (!bc.empty()) {
      o << "\n**Table 4.10 analogue: B-Convert (truncate) false pixels at row ends (each end counted on its own).**\n\n"
           "| mesh | size | 0 | 1 | 2 | 3+ |\n| --- | ---: | ---: | ---: | ---: | ---: |\n";
      for (const auto& m : ix.meshes)
        for (uint32_t s : ix.sizes)
          if (const ScanBenchRow* r = ix.at(bc, m, s))
            o << "| " << m << " | " << s << "² | " << thousands(r->row_end_misses[0]) << " | "
              << thousands(r->row_end_misses[1]) << " | " << thousands(r->row_end_misses[2]) << " | "
              << thousands(r->row_end_misses[3]) << " |\n";
    }
    md = o.str();
  }
  {
    AtomicFile out((std::filesystem::path(dir) / "tables.md").string());
    std::ofstream f(out.temp_path());
    f << md;
    f.close();
    out.commit();
  }
  // Figures: per mesh, list + scan time vs resolution for every strategy.
  for (const auto& m : ix.meshes) {
    std::vector<PlotSeries> series;
    for (const auto& [l, map] : ix.by_label) {
      PlotSeries s{l, {}, {}, {}};
      for (uint32_t sz : ix.sizes)
        if (const ScanBenchRow* r = ix.at(l, m, sz)) s.x.push_back(sz), s.y.push_back(r->total_ms);
      if (!s.x.empty()) series.push_back(s);
    }
    PlotSpec spec;
    spec.title = m + ": scan-convert time (list generation + pixel loop)";
    spec.xlabel = "image size (pixels per side)";
    spec.ylabel = "ms";
    write_line_plot((std::filesystem::path(dir) / (m + "-time.png")).string(), spec, series);
  }
}

}  // namespace zs
