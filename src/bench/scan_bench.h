// `zsweep bench scan`: the seed's experiment (B-Convert digest §7–9) on this machine —
// every strategy and B-Convert variant, per mesh and resolution, whole ZSweep
// renders with one thread, with times split into list generation (per-face
// set-up) and scan conversion (the pixel loop), hit/miss counts, pixels the
// bounding box finds that a strategy misses, and image differences.
#pragma once

#include <string>
#include <vector>

#include "raster/bconvert_scan.h"
#include "render/volume/render_settings.h"

namespace zs {

struct ScanBenchOptions {
  std::vector<std::string> inputs;  // scene .json or mesh files
  std::vector<uint32_t> sizes{512, 1024, 2048};
  std::vector<ScanStrategy> strategies{ScanStrategy::BBox, ScanStrategy::BConvert, ScanStrategy::Span};
  std::vector<BConvertVariant> variants{BConvertVariant::Truncate};
  std::string csv, plots_dir;
  int repeat = 1;
  uint64_t memory_budget_bytes = 0;
  bool progress = true;
  // Sizes above this run raster-only (no compositing, no image): the
  // scan-convert counts and times are the same, the render time is not.
  uint32_t raster_only_above = 8192;
};

struct ScanBenchRow {
  std::string mesh, strategy, variant;
  uint32_t size = 0;
  double list_generation_ms = 0, scan_convert_ms = 0, total_ms = 0, render_ms = 0;
  uint64_t pixel_tests = 0, pixel_hits = 0, pixel_misses = 0, missing_pixels = 0, rendered_pixels = 0;
  double image_max_abs_diff = -1;  // -1: not compared (image too large to keep)
  double face_to_bbox_area_ratio = 0, mean_face_area_px = 0;
  uint64_t faces_projected = 0, bconvert_fallbacks = 0;
  uint64_t row_end_misses[4] = {0, 0, 0, 0};
};

std::vector<ScanBenchRow> run_scan_bench(const ScanBenchOptions& opt);
void write_scan_bench_csv(const std::string& path, const std::vector<ScanBenchRow>& rows);
// Reads rows back from CSVs written by write_scan_bench_csv (to merge runs).
std::vector<ScanBenchRow> read_scan_bench_csv(const std::string& path);
// Figures (time vs resolution per mesh, log scales) and tables.md mirroring
// the seed's Tables 4.2-4.10, into dir.
void write_scan_bench_report(const std::string& dir, const std::vector<ScanBenchRow>& rows);

}  // namespace zs
