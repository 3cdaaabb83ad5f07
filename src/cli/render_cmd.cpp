// `zsweep render SCENE.json -o OUT` or `zsweep render MESH -o OUT` (automatic
// camera and transfer function), or `zsweep render -o OUT` for the embedded
// default scene.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/json_out.h"
#include "cli/render_mpi.h"
#include "cli/render_surfaces.h"
#include "cli/scene_args.h"
#include "image/tile_writer.h"
#include "mesh/topology.h"
#include "mesh/validate.h"
#include "view/camera.h"
#include "scene/scene.h"
#include "spheres/sphere_colors.h"
#include "sprites/sphere_ao.h"
#include "sprites/sphere_renderer.h"
#include "util/atomic_file.h"
#include "util/bytes_str.h"
#include "util/memory.h"
#include "volume/segment_batch.h"
#include "volume/zsweep_renderer.h"

namespace zs {

namespace {

void write_stats(const std::string& path, const RenderStats& S, const Scene& scene, const TetMesh& m,
                 double ms_load, double ms_topology, const std::vector<double>& frame_ms = {}) {
  nlohmann::json j = {
      {"time_ms",
       {{"total", S.ms_total},
        {"setup", S.ms_setup},
        {"order", S.ms_order},
        {"binning", S.ms_binning},
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
      {"peak_overflow_fragments", S.peak_overflow_fragments},
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
      {"precision", scene.settings.single_precision ? "single" : "double"},
      // The batched kernel, where segments are batched (exact, no early termination).
      {"kernel", scene.settings.integrator == Integrator::Exact && scene.settings.early_termination <= 0
                     ? kernel_name(best_kernel_width(), scene.settings.single_precision ? KernelPrecision::Single
                                                                                        : KernelPrecision::Double)
                     : "none"},
      {"tiles", S.tiles},
      {"tile_size", S.tile_size},
  };
  // --frames N: every frame's total; time_ms.total is the best of them.
  if (frame_ms.size() > 1) j["frame_ms"] = frame_ms;
  write_json_file(path, j);
}

// Input that renders, but not as the user likely meant: one warning line
// each on stderr; the image is still written and the exit code is 0.
void warn_nonfinite(const SceneInput& in) {
  const size_t n = count_nonfinite_tets(in.mesh);
  if (n == 0) return;
  const std::string name = in.scene.mesh_path.empty() ? "default mesh" : in.scene.mesh_path;
  std::fprintf(stderr, "zsweep: warning: %s: %zu of %zu tets have a non-finite coordinate or scalar; they are left out\n",
               name.c_str(), n, in.mesh.num_tets());
}

void warn_if_empty(const SceneInput& in, const RenderStats& st, const std::string& out_path) {
  if (st.rendered_pixels > 0) return;
  const RenderSettings& rs = in.scene.settings;
  const View view(rs.camera, rs.width, rs.height);
  bool in_front = false, any_depth = false;
  for (const glm::dvec3& p : in.mesh.points) {
    const double z = view.project(p).z;
    any_depth |= std::isfinite(z);
    in_front |= z > 0;
  }
  const size_t tets = in.mesh.num_tets();
  const char* why = !any_depth ? "the camera cannot resolve the mesh at this scale (depths are not finite)"
                    : !in_front                                      ? "the whole mesh is behind the camera"
                    : count_nonfinite_tets(in.mesh) == tets          ? "every tet has a non-finite coordinate or scalar"
                    : st.tets_invisible + st.tets_degenerate >= tets ? "the transfer function's opacity is zero "
                                                                       "wherever the mesh is (or its cells are flat)"
                    : st.faces_projected == 0                        ? "the mesh is outside the view"
                                                                     : "no fragment reached a pixel";
  std::fprintf(stderr, "zsweep: warning: %s: the image is empty: %s\n", out_path.c_str(), why);
}

// Renders `frames - 1` untimed-for-output frames before the written one, each
// a whole frame (setup included), as a viewer re-rendering a new view would:
// benchmarks time steady-state frames in one process (no loader, no cold
// page faults) and report the best. `make` builds a renderer (its setup is
// part of the frame), `total_ms` reads a finished frame's time.
template <class R, class Make, class Total>
std::unique_ptr<R> render_frames(int frames, ImageTileWriter& writer, const Make& make, const Total& total_ms,
                                 std::vector<double>* frame_ms) {
  struct Discard : TileSink {
    void tile(const TileRect&, const float*) override {}
  } discard;
  for (int f = 1; f < frames; ++f) {
    std::unique_ptr<R> r = make();
    r->render_tiles(discard, nullptr);
    frame_ms->push_back(total_ms(*r));
  }
  std::unique_ptr<R> r = make();
  r->render_tiles(writer, nullptr);
  writer.commit();
  frame_ms->push_back(total_ms(*r));
  return r;
}

// Sphere scenes (src/sprites/): the same tiles, threads, streaming writers,
// budget and MPI as volume scenes, through the renderer interface.
void write_sphere_stats(const std::string& path, const SphereStats& S, const SceneInput& in, SphereColorMode color,
                        const std::vector<double>& frame_ms) {
  const VisibilityStats& V = S.vis;
  nlohmann::json j = {
      {"renderer", "spheres"},
      {"time_ms",
       {{"total", S.ms_total},
        {"setup", S.ms_setup},
        {"visibility", S.ms_visibility},
        {"view_culling", V.ms_view},
        {"occlusion_culling", V.ms_occlusion},
        {"pyramid", V.ms_pyramid},
        {"binning", S.ms_binning},
        {"grid", S.ms_grid},
        {"ao_maps", S.ms_ao_maps},
        {"load", in.ms_load}}},
      {"ao",
       {{"directions", in.scene.spheres.ao.directions},
        {"map_size", in.scene.spheres.ao.map_size},
        {"depth", in.scene.spheres.ao.impostor_depth ? "impostor" : "disc"},
        {"occluders", in.scene.spheres.ao.alpha_occluders ? "alpha" : "opaque"},
        {"map_bytes", S.ao_map_bytes},
        {"batches", S.ao_batches},
        {"translucent_fragments", S.ao_translucent_fragments}}},
      {"spheres", {{"total", S.spheres}, {"invalid", S.invalid}, {"skipped_by_reader", in.spheres.invalid}}},
      {"culling",
       {{"enabled", in.scene.spheres.culling},
        {"grid", std::lround(std::cbrt(double(V.cells)))},  // as built ("auto" resolved)
        {"cells", V.cells},
        {"cells_empty", V.cells_empty},
        {"cells_view_culled", V.cells_view_culled},
        {"cells_occluded", V.cells_occluded},
        {"spheres_view_culled", V.spheres_view_culled},
        {"spheres_in_occluded_cells", V.spheres_occluded_cells},
        {"spheres_pyramid_culled", V.spheres_pyramid_culled},
        {"spheres_pixel_culled", V.spheres_pixel_culled},
        {"spheres_offscreen", V.spheres_offscreen},
        {"occluders", V.occluders},
        {"spheres_visible", V.spheres_visible}}},
      {"spheres_scanned", S.spheres_scanned},
      {"spheres_block_rejected", S.spheres_block_rejected},
      {"pixel_tests", S.pixel_tests},
      {"fragments", S.fragments},
      {"fragments_early_rejected", S.early_rejected},
      {"depth_writes", S.depth_writes},
      {"rendered_pixels", S.rendered_pixels},
      {"bin_entries", S.bin_entries},
      {"tiles", S.tiles},
      {"tile_size", S.tile_size},
      {"mode", to_string(in.scene.spheres.mode)},
      {"color", to_string(color)},
      {"image", {{"width", in.scene.settings.width}, {"height", in.scene.settings.height}}},
      {"peak_rss_bytes", S.peak_rss_bytes},
      {"memory_budget_bytes", S.memory_budget_bytes},
  };
  if (in.scene.spheres.mode != SphereMode::Opaque) {
    const SphereScene& sp = in.scene.spheres;
    j["translucency"] = {
        {"surfaces", sp.front_surfaces_only ? "front" : "both"},
        {"tolerance", sp.tolerance},
        {"max_layers", sp.max_layers},
        {"fragments_composited", S.composited},
        {"pixels_stopped", S.pixels_stopped},
        {"spheres_clear", S.spheres_clear},
        {"passes", S.passes},
        {"layers_max", S.layers_max},
        {"layers_mean", S.layer_pixels ? double(S.layer_sum) / double(S.layer_pixels) : 0.0},
    };
  }
  if (frame_ms.size() > 1) j["frame_ms"] = frame_ms;
  write_json_file(path, j);
}

void run_spheres(SceneInput& in, const std::string& out_path, const std::string& stats_path, int frames,
                 const std::string& compression, bool no_culling) {
  using Clock = std::chrono::steady_clock;
  SphereScene& sp = in.scene.spheres;
  if (no_culling) sp.culling = false;
  const RenderSettings& rs = in.scene.settings;
  SphereRenderSettings srs = sphere_render_settings(rs, sp);
  const SphereColorMode color = sp.has_color_mode ? sp.color : default_color_mode(in.spheres);
  std::vector<glm::vec4> colors;
  try {
    colors = sphere_colors(in.spheres, color, rs.tf);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(sp.path + ": " + e.what());
  }
  const auto t0 = Clock::now();
  const SphereGrid g = build_sphere_grid(in.spheres, srs.grid);
  const double ms_grid = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const TileGrid grid{rs.width, rs.height, rs.tile_size, sphere_channels(srs)};
  const std::vector<std::string> names =
      srs.ao.directions ? std::vector<std::string>{"R", "G", "B", "A", "Z", "AO"} : std::vector<std::string>{};
  const uint64_t held = sphere_set_bytes(in.spheres) + colors.size() * sizeof(glm::vec4);
  // AO maps: built once for the set and shared by every frame (they do not
  // depend on the view), when they fit the budget; else every frame builds
  // and consumes them in batches (the renderer says when it cannot).
  std::shared_ptr<const SphereAoMaps> ao;
  if (srs.ao.directions) {
    const uint64_t budget = srs.memory_budget_bytes ? srs.memory_budget_bytes : default_memory_budget();
    ao = sphere_ao_maps(in.spheres, colors, srs, budget > held ? budget - held : 0);
    if (!ao) srs.ao.batches = true;
  }
  if (render_mpi_enabled()) {
    std::unique_ptr<ImageTileWriter> w;
    if (render_mpi_rank() == 0) w = std::make_unique<ImageTileWriter>(out_path, grid, compression, names);
    srs.progress = false;
    SphereRenderer r(in.spheres, colors, g, srs,
                     held + (w ? w->buffer_bytes_estimate() : 0) + render_mpi_message_bytes(grid, srs.threads), ao);
    MpiReport report;
    render_mpi(r, w.get(), &report);
    if (!w) return;
    w->commit();
    SphereStats st = r.stats();
    st.ms_grid = ms_grid;
    if (ao) st.ms_ao_maps = ao->ms_build;
    st.ms_total = st.ms_setup + report.wall_ms;
    for (uint64_t p : report.peak_rss) st.peak_rss_bytes = std::max(st.peak_rss_bytes, p);
    if (!stats_path.empty()) write_sphere_stats(stats_path, st, in, color, {});
    std::printf("wrote %s: %ux%u, %llu spheres drawn of %llu, %llu rendered pixels, %.1f ms\n", out_path.c_str(),
                rs.width, rs.height, (unsigned long long)st.vis.spheres_visible, (unsigned long long)st.spheres,
                (unsigned long long)st.rendered_pixels, st.ms_total);
    return;
  }
  ImageTileWriter writer(out_path, grid, compression, names);
  std::vector<double> frame_ms;
  auto renderer = render_frames<SphereRenderer>(
      frames, writer,
      [&] {
        return std::make_unique<SphereRenderer>(in.spheres, colors, g, srs, held + writer.buffer_bytes_estimate(), ao);
      },
      [](const SphereRenderer& r) { return r.stats().ms_total; }, &frame_ms);
  SphereStats st = renderer->stats();
  st.ms_grid = ms_grid;
  if (ao) st.ms_ao_maps = ao->ms_build;
  if (frames > 1) st.ms_total = *std::min_element(frame_ms.begin(), frame_ms.end());
  if (st.rendered_pixels == 0)
    std::fprintf(stderr, "zsweep: warning: %s: the image is empty: no sphere is in front of the camera and in view\n",
                 out_path.c_str());
  if (!stats_path.empty()) write_sphere_stats(stats_path, st, in, color, frame_ms);
  std::printf("wrote %s: %ux%u, %llu spheres drawn of %llu, %llu rendered pixels, %.1f ms\n", out_path.c_str(),
              rs.width, rs.height, (unsigned long long)st.vis.spheres_visible, (unsigned long long)st.spheres,
              (unsigned long long)st.rendered_pixels, st.ms_total);
}

void run(const SceneArgs& a, const std::string& out_path, const std::string& stats_path, int frames,
         const std::string& compression, bool no_culling) {
  using Clock = std::chrono::steady_clock;
  SceneInput in = a.load();
  if (in.scene.kind == SceneKind::Spheres) {
    if (!stats_path.empty()) AtomicFile(stats_path).check_writable();
    return run_spheres(in, out_path, stats_path, frames, compression, no_culling);
  }
  if (in.scene.kind == SceneKind::Surfaces) {
    if (!stats_path.empty()) AtomicFile(stats_path).check_writable();
    if (no_culling) in.scene.surfaces.cull_back = in.scene.surfaces.cull_view = false;
    return run_surfaces(in, out_path, stats_path, frames, compression);
  }
  if (!stats_path.empty()) AtomicFile(stats_path).check_writable();  // not after the render
  if (!render_mpi_enabled() || render_mpi_rank() == 0) warn_nonfinite(in);
  RenderSettings& rs = in.scene.settings;
  rs.face_area_stats = !stats_path.empty();
  const auto t1 = Clock::now();
  const Topology topo = build_topology(in.mesh);
  const auto t2 = Clock::now();
  const double ms_topology = std::chrono::duration<double, std::milli>(t2 - t1).count();
  const TileGrid grid{rs.width, rs.height, rs.tile_size};
  // The budget before the output opens: the file library allocates its tile
  // tables then (2 GiB for a 1048576² EXR), and an image the format cannot
  // hold is refused here too.
  check_memory_budget(in.mesh, topo, rs, ImageTileWriter::buffer_bytes_estimate(out_path, grid));
  // ---- MPI: `render --mpi` (src/cli/render_mpi.h). Every rank sweeps a share
  // of the tiles into rank 0's writer; rank 0 alone writes and prints. ----
  if (render_mpi_enabled()) {
    std::unique_ptr<ImageTileWriter> w;
    if (render_mpi_rank() == 0) w = std::make_unique<ImageTileWriter>(out_path, grid, compression);
    RenderSettings quiet = rs;  // outlives the renderer, which keeps a reference
    quiet.progress = false;
    ZSweepRenderer r(in.mesh, topo, quiet,
                     (w ? w->buffer_bytes_estimate() : 0) + render_mpi_message_bytes(grid, quiet.threads));
    MpiReport report;
    render_mpi(r, w.get(), &report);
    if (!w) return;
    w->commit();
    RenderStats st = r.stats();
    st.ms_total = st.ms_setup + report.wall_ms;
    for (uint64_t p : report.peak_rss) st.peak_rss_bytes = std::max(st.peak_rss_bytes, p);
    warn_if_empty(in, st, out_path);
    if (!stats_path.empty()) write_stats(stats_path, st, in.scene, in.mesh, in.ms_load, ms_topology);
    std::printf("wrote %s: %ux%u, %llu fragments, %llu rendered pixels, %.1f ms\n", out_path.c_str(), rs.width,
                rs.height, (unsigned long long)st.fragments, (unsigned long long)st.rendered_pixels, st.ms_total);
    return;
  }
  // ---- end MPI ----
  // Tiles stream from the engine into the file as they finish, so no
  // format needs the whole image in memory (EXR/TIFF tiled, PNG in row
  // bands) and stills larger than memory work. The writer opens first, so an
  // unwritable path fails before the render, and its buffers count against
  // the budget; nothing appears under out_path unless commit() succeeds.
  ImageTileWriter writer(out_path, grid, compression);
  std::vector<double> frame_ms;
  auto renderer = render_frames<ZSweepRenderer>(
      frames, writer, [&] { return std::make_unique<ZSweepRenderer>(in.mesh, topo, rs, writer.buffer_bytes_estimate()); },
      [](const ZSweepRenderer& r) { return r.stats().ms_total; }, &frame_ms);
  RenderStats stats = renderer->stats();
  stats.peak_rss_bytes = std::max(stats.peak_rss_bytes, peak_rss_bytes());
  warn_if_empty(in, stats, out_path);
  if (frames > 1) stats.ms_total = *std::min_element(frame_ms.begin(), frame_ms.end());
  if (!stats_path.empty()) write_stats(stats_path, stats, in.scene, in.mesh, in.ms_load, ms_topology, frame_ms);
  std::printf("wrote %s: %ux%u, %llu fragments, %llu rendered pixels, %.1f ms\n", out_path.c_str(), rs.width,
              rs.height, (unsigned long long)stats.fragments, (unsigned long long)stats.rendered_pixels,
              stats.ms_total);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>(), stats = std::make_shared<std::string>();
  auto frames = std::make_shared<int>(1);
  auto compression = std::make_shared<std::string>();
  auto no_culling = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("render", "Render a scene (.json), a mesh, or the embedded default scene");
  a->add_options(*cmd, true);
  cmd->add_option("-o,--output", *out, "Output image: .png (8-bit), .exr or .tif (float)")->required();
  cmd->add_option("--stats", *stats, "Write render statistics as JSON");
  cmd->add_option("--frames", *frames,
                  "Render N whole frames (setup included) in one process and write the last; --stats reports "
                  "the best frame's time (steady-state benchmarks)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--compression", *compression,
                  "EXR/TIFF compression. EXR lossless: rle (default: fast), zip (smaller files, ~4x slower to "
                  "write), zips, piz, none; EXR lossy: pxr24, b44, b44a, dwaa, dwab. TIFF (lossless): zip "
                  "(default), lzw, packbits, none");
  cmd->add_flag("--no-culling", *no_culling,
                 "Sphere scenes: draw every sphere, without the (lossless) visibility culling; surface scenes: no "
                 "back-face or view-volume culling");
  add_render_mpi_options(*cmd);  // --mpi, --mpi-schedule (src/cli/render_mpi.h)
  cmd->callback([a, out, stats, frames, compression, no_culling] { run(*a, *out, *stats, *frames, *compression, *no_culling); });
}

}  // namespace zs
