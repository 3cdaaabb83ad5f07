// `zsweep bench accuracy`: the speed/accuracy trade, measured. Every ZSweep
// setting a user can turn — integrator, scan strategy and B-Convert variant,
// early-termination threshold, maximum list length, and rendering at a lower
// resolution — is timed and compared with the reference ray caster
// (reference_renderer.h) rendered once per scene and size.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace zs {

struct AccuracyBenchOptions {
  std::vector<std::string> inputs;  // scene .json, mesh files, or "default" (embedded scene)
  std::vector<uint32_t> sizes{512};
  // Axes to run: integrator, scan, early-termination, max-list, resolution.
  std::vector<std::string> groups{"integrator", "scan", "early-termination", "max-list", "resolution"};
  std::string csv, plots_dir;
  int repeat = 1, threads = 1;
};

struct AccuracyRow {
  std::string scene, group, setting;
  uint32_t size = 0;         // the image compared (and the reference's size)
  uint32_t render_size = 0;  // what was rendered (smaller for the resolution group)
  double ms = 0, reference_ms = 0;
  double max_abs = 0, rmse = 0, psnr = 0;
  uint64_t pixels_over_1_255 = 0, fragments = 0, early_terminated_pixels = 0;
  double bound = -1;  // stated error bound for this setting (-1: none)
};

std::vector<AccuracyRow> run_accuracy_bench(const AccuracyBenchOptions& opt);
void write_accuracy_csv(const std::string& path, const std::vector<AccuracyRow>& rows);
// Per scene and size: time-vs-error scatter (accuracy-SCENE-SIZE.png) and the
// early-termination bound figure (et-bound-SCENE-SIZE.png).
void write_accuracy_plots(const std::string& dir, const std::vector<AccuracyRow>& rows);

}  // namespace zs
