#include "app/scene_args.h"

#include <algorithm>
#include <stdexcept>
#include <thread>

#include <CLI/CLI.hpp>

namespace zs {

void SceneArgs::add_options(CLI::App& cmd, bool engine_knobs) {
  cmd.add_option("input", input, "Scene .json, or a mesh (automatic camera and transfer function)");
  cmd.add_option("--threads", threads, "Threads (default: every core); images are identical for any count")
      ->check(CLI::Range(1, 1024));
  cmd.add_option("--q", opt.q_path, "PLOT3D solution file (mesh input)");
  cmd.add_option("--scalar", opt.scalar, "Point array or PLOT3D function (mesh input)");
  cmd.add_option("--width", width, "Override image width")->check(CLI::Range(1u, 1u << 20));
  cmd.add_option("--height", height, "Override image height")->check(CLI::Range(1u, 1u << 20));
  cmd.add_option("--projection", projection, "Automatic camera: orthographic (default) or perspective");
  cmd.add_option("--memory-budget", memory_budget_mb, "Memory budget in MiB (default: half of physical memory)")
      ->check(CLI::Range(0.001, 1.7e13));
  if (!engine_knobs) return;
  cmd.add_option("--scan", scan, "Scan strategy: span (default), bbox (same image, slower), bconvert");
  cmd.add_option("--variant", variant, "B-Convert variant: truncate, round, dilate, dda3d, runlength");
  cmd.add_option("--integrator", integrator, "exact, linear, preintegrated or taylor2");
  cmd.add_option("--precision", precision,
                 "Exact integrator's kernel: double (default) or single (faster; error bound in docs/accuracy.md)");
  cmd.add_option("--early-termination", early_termination, "Stop a pixel below t/510 transmittance (t in 8-bit levels)");
  cmd.add_option("--max-list-length", max_list_length, "Force compositing when a pixel list grows past this");
  cmd.add_option("--tile-size", tile_size, "Screen tile size in pixels (default 64); the image does not depend on it")
      ->check(CLI::Range(8u, 4096u));
}

SceneInput SceneArgs::load() const {
  check();  // before any file is read
  SceneInput in = load_scene_input(input, opt);
  apply(in);
  return in;
}

RenderSettings SceneArgs::check() const {
  if (!projection.empty() && projection != "perspective" && projection != "orthographic")
    throw std::runtime_error("--projection must be orthographic or perspective");
  RenderSettings knobs;
  if (!scan.empty() && !parse_scan_strategy(scan, &knobs.scan))
    throw std::runtime_error("--scan must be bbox, bconvert or span");
  if (!variant.empty() && !parse_bconvert_variant(variant, &knobs.bconvert_variant))
    throw std::runtime_error("--variant must be truncate, round, dilate, dda3d or runlength");
  if (!integrator.empty() && !parse_integrator(integrator, &knobs.integrator))
    throw std::runtime_error("--integrator must be exact, linear, preintegrated or taylor2");
  if (!precision.empty() && precision != "double" && precision != "single")
    throw std::runtime_error("--precision must be double or single");
  return knobs;
}

void SceneArgs::apply(SceneInput& in) const {
  const RenderSettings knobs = check();
  Projection p = projection == "perspective" ? Projection::Perspective : Projection::Orthographic;
  RenderSettings& rs = in.scene.settings;
  if (width) rs.width = width;
  if (height) rs.height = height;
  if (!scan.empty()) rs.scan = knobs.scan;
  if (!variant.empty()) rs.bconvert_variant = knobs.bconvert_variant;
  if (!integrator.empty()) rs.integrator = knobs.integrator;
  if (!precision.empty()) rs.single_precision = precision == "single";
  if (memory_budget_mb > 0) rs.memory_budget_bytes = uint64_t(memory_budget_mb * 1048576.0);
  if (early_termination >= 0) rs.early_termination = early_termination;
  if (max_list_length >= 0) rs.max_list_length = uint32_t(max_list_length);
  if (tile_size) rs.tile_size = tile_size;
  rs.threads = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  rs.progress = true;
  // Surfaces are framed in perspective unless told otherwise.
  if (projection.empty() && in.scene.kind == SceneKind::Surfaces) p = Projection::Perspective;
  finish_scene(in, p);
}

}  // namespace zs
