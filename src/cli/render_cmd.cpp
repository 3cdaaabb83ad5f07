// `zsweep render SCENE.json -o OUT` or `zsweep render MESH -o OUT` (automatic
// camera and transfer function), or `zsweep render -o OUT` for the embedded
// default scene.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <thread>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/mesh_source.h"
#include "image/image.h"
#include "mesh/default_mesh.h"
#include "mesh/topology.h"
#include "scene/scene.h"
#include "util/atomic_file.h"
#include "volume/zsweep_renderer.h"

namespace zs {

namespace {

struct RenderArgs {
  std::string input;  // scene .json, mesh, or empty (default scene)
  ReadOptions opt;
  std::string out, stats;
  int threads = 0;  // 0 = every core
  uint32_t width = 0, height = 0;
  std::string scan, variant, integrator, projection;
  double memory_budget_mb = 0;
  double early_termination = -1;
  int64_t max_list_length = -1;
};

bool ends_with(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

// The embedded default scene: the default ball of blobs, seen obliquely.
Scene default_scene() {
  Scene s;
  RenderSettings& rs = s.settings;
  rs.width = rs.height = 512;
  rs.camera.projection = Projection::Perspective;
  rs.camera.eye = {2.6, 1.6, 3.4};
  rs.camera.target = {0, 0, 0};
  rs.camera.up = {0, 1, 0};
  rs.camera.fov_y = 35;
  rs.background[0] = rs.background[1] = rs.background[2] = 0.0;
  rs.background[3] = 1.0;
  rs.tf = TransferFunction({{0.0, 0.1, 0.2, 0.6}, {0.3, 0.1, 0.7, 0.8}, {0.6, 0.95, 0.85, 0.3}, {1.0, 0.9, 0.2, 0.1}},
                           {{0.0, 0.0}, {0.15, 0.0}, {0.35, 0.08}, {0.6, 0.25}, {1.0, 0.8}}, 0.1);
  s.has_camera = s.has_transfer_function = true;
  return s;
}

void write_stats(const std::string& path, const RenderStats& S, const Scene& scene, const TetMesh& m,
                 double ms_load, double ms_topology) {
  nlohmann::json j = {
      {"time_ms",
       {{"total", S.ms_total},
        {"setup", S.ms_setup},
        {"list_generation", S.ms_list_generation},
        {"scan_convert", S.ms_scan_convert},
        {"insert", S.ms_insert},
        {"composite", S.ms_composite},
        {"load", ms_load},
        {"topology", ms_topology}}},
      {"pixel_tests", S.pixel_tests},
      {"pixel_hits", S.pixel_hits},
      {"pixel_misses", S.pixel_misses},
      {"fragments", S.fragments},
      {"rendered_pixels", S.rendered_pixels},
      {"faces_projected", S.faces_projected},
      {"faces_culled", S.faces_culled},
      {"faces_offscreen", S.faces_offscreen},
      {"faces_degenerate", S.faces_degenerate},
      {"faces_clipped", S.faces_clipped},
      {"tets_invisible", S.tets_invisible},
      {"tets_degenerate", S.tets_degenerate},
      {"max_list_length", S.max_list_length},
      {"forced_composites", S.forced_composites},
      {"budget_flushes", S.budget_flushes},
      {"composite_events", S.composite_events},
      {"segments", S.segments},
      {"early_terminated_pixels", S.early_terminated_pixels},
      {"peak_fragments", S.peak_fragments},
      {"peak_rss_bytes", S.peak_rss_bytes},
      {"memory_budget_bytes", S.memory_budget_bytes},
      {"mesh", {{"points", m.num_points()}, {"tets", m.num_tets()}}},
      {"image", {{"width", scene.settings.width}, {"height", scene.settings.height}}},
      {"scan", to_string(scene.settings.scan)},
      {"bconvert_variant", to_string(scene.settings.bconvert_variant)},
      {"bconvert_fallbacks", S.bconvert_fallbacks},
      {"row_end_misses", {S.row_end_misses[0], S.row_end_misses[1], S.row_end_misses[2], S.row_end_misses[3]}},
      {"face_to_bbox_area_ratio", S.bbox_area > 0 ? S.face_area / S.bbox_area : 0.0},
      {"integrator", to_string(scene.settings.integrator)},
  };
  AtomicFile out(path);
  {
    std::ofstream f(out.temp_path());
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error(path + ": cannot write stats");
  }
  out.commit();
}

void run(const RenderArgs& a) {
  using Clock = std::chrono::steady_clock;
  Scene scene;
  if (a.input.empty()) {
    scene = default_scene();
  } else if (ends_with(a.input, ".json")) {
    scene = load_scene(a.input);
  } else {
    scene.mesh_path = a.input;
    scene.mesh_options = a.opt;
  }
  RenderSettings& rs = scene.settings;
  if (a.width) rs.width = a.width;
  if (a.height) rs.height = a.height;
  if (!a.scan.empty() && !parse_scan_strategy(a.scan, &rs.scan))
    throw std::runtime_error("--scan must be bbox, bconvert or span");
  if (!a.variant.empty() && !parse_bconvert_variant(a.variant, &rs.bconvert_variant))
    throw std::runtime_error("--variant must be truncate, round, dilate, dda3d or runlength");
  if (!a.integrator.empty() && !parse_integrator(a.integrator, &rs.integrator))
    throw std::runtime_error("--integrator must be exact, linear or preintegrated");
  if (a.memory_budget_mb > 0) rs.memory_budget_bytes = uint64_t(a.memory_budget_mb * 1048576.0);
  if (a.early_termination >= 0) rs.early_termination = a.early_termination;
  if (a.max_list_length >= 0) rs.max_list_length = uint32_t(a.max_list_length);
  rs.threads = a.threads > 0 ? a.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  rs.progress = true;
  rs.face_area_stats = !a.stats.empty();

  const auto t0 = Clock::now();
  const TetMesh mesh = scene.mesh_path.empty() ? default_mesh() : read_mesh(scene.mesh_path, scene.mesh_options);
  const auto t1 = Clock::now();
  if (mesh.num_tets() == 0) throw std::runtime_error(scene.mesh_path + ": mesh has no tets");
  if (!scene.has_camera) {
    Projection p = Projection::Orthographic;
    if (a.projection == "perspective") p = Projection::Perspective;
    else if (!a.projection.empty() && a.projection != "orthographic")
      throw std::runtime_error("--projection must be orthographic or perspective");
    rs.camera = auto_camera(mesh, p, rs.width, rs.height);
  }
  if (!scene.has_transfer_function) rs.tf = default_transfer_function(mesh);
  const Topology topo = build_topology(mesh);
  const auto t2 = Clock::now();
  RenderStats stats;
  const Image img = render_zsweep(mesh, topo, rs, &stats);
  write_image(a.out, img);
  if (!a.stats.empty())
    write_stats(a.stats, stats, scene, mesh,
                std::chrono::duration<double, std::milli>(t1 - t0).count(),
                std::chrono::duration<double, std::milli>(t2 - t1).count());
  std::printf("wrote %s: %ux%u, %llu fragments, %llu rendered pixels, %.1f ms\n", a.out.c_str(), rs.width,
              rs.height, (unsigned long long)stats.fragments, (unsigned long long)stats.rendered_pixels,
              stats.ms_total);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene (.json), a mesh, or the embedded default scene");
  cmd->add_option("input", a->input, "Scene .json, or a mesh (automatic camera and transfer function)");
  cmd->add_option("-o,--output", a->out, "Output image: .png (8-bit), .exr or .tif (float)")->required();
  cmd->add_option("--stats", a->stats, "Write render statistics as JSON");
  cmd->add_option("--threads", a->threads, "Threads (default: every core); images are identical for any count")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--q", a->opt.q_path, "PLOT3D solution file (mesh input)");
  cmd->add_option("--scalar", a->opt.scalar, "Point array or PLOT3D function (mesh input)");
  cmd->add_option("--width", a->width, "Override image width")->check(CLI::Range(1u, 1u << 20));
  cmd->add_option("--height", a->height, "Override image height")->check(CLI::Range(1u, 1u << 20));
  cmd->add_option("--scan", a->scan, "Scan strategy: bbox, bconvert, span");
  cmd->add_option("--variant", a->variant, "B-Convert variant: truncate, round, dilate, dda3d, runlength");
  cmd->add_option("--integrator", a->integrator, "exact, linear or preintegrated");
  cmd->add_option("--projection", a->projection, "Automatic camera: orthographic (default) or perspective");
  cmd->add_option("--memory-budget", a->memory_budget_mb, "Memory budget in MiB (default: half of physical memory)");
  cmd->add_option("--early-termination", a->early_termination, "Stop a pixel below t/510 transmittance (t in 8-bit levels)");
  cmd->add_option("--max-list-length", a->max_list_length, "Force compositing when a pixel list grows past this");
  cmd->callback([a] { run(*a); });
}

}  // namespace zs
