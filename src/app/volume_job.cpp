// Volume scenes: the ZSweep engine (src/render/volume/) on a tet mesh.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "app/scene_jobs.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "base/util/bytes_str.h"
#include "base/util/memory.h"
#include "base/view/camera.h"
#include "render/volume/render_plan.h"
#include "render/volume/segment_batch.h"
#include "render/volume/volume_memory.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {

namespace {

class VolumeJob : public SceneJob {
 public:
  explicit VolumeJob(SceneInput& in) : in_(in), rs_(in.scene.settings) {
    const TetMesh& m = in.mesh;
    // Refused before anything is built when the mesh cannot fit the budget
    // (the kernel would otherwise kill the process halfway).
    const VolumeMemory need = estimate_volume_memory(m.num_points(), m.num_tets(), m.has_scalars(), 0, m.has_cell_scalars());
    if (need.peak() > rs_.budget())
      throw std::runtime_error((in.scene.mesh_path.empty() ? std::string() : in.scene.mesh_path + ": ") +
                               "memory budget of " + bytes_str(rs_.budget()) + " cannot hold this mesh: " +
                               std::to_string(m.num_tets()) + " tets need about " + volume_memory_summary(need) +
                               " (--memory-budget)");
    const auto t0 = std::chrono::steady_clock::now();
    // The view-independent state, built once for every frame, on the
    // render's threads.
    tbb::task_arena(std::max(1, rs_.threads)).execute([&] { topo_ = build_topology(m); });
    nonfinite_tets_ = topo_.num_nonfinite_tets;
    ms_topology_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    grid_ = TileGrid{rs_.width, rs_.height, rs_.tile_size};
    // What every frame shares is counted against the budget with the
    // caller's own bytes.
    held_ = estimate_volume_memory(m.num_points(), m.num_tets(), m.has_scalars(), topo_.num_faces(),
                                   m.has_cell_scalars());
  }
  bool set_camera(const Camera& camera) override {
    rs_.camera = camera;
    return true;
  }
  void check_budget(uint64_t extra_bytes) const override {
    check_memory_budget(in_.mesh, topo_, rs_, extra_bytes + held_.mesh + held_.topology);
  }
  std::unique_ptr<TiledRenderer> renderer(uint64_t extra_bytes, bool progress) override {
    rs_.progress = progress;  // the renderer keeps a reference to rs_
    return std::make_unique<ZSweepRenderer>(in_.mesh, topo_, rs_, extra_bytes + held_.mesh + held_.topology, &buffers_);
  }
  double total_ms(const TiledRenderer& r) const override { return of(r).stats().ms_total; }
  nlohmann::json stats(const TiledRenderer& r, const FrameReport& f) const override;
  std::string summary(const TiledRenderer& r, double total_ms) const override {
    const RenderStats S = of(r).stats();
    char line[256];
    std::snprintf(line, sizeof line, "%ux%u, %llu fragments, %llu rendered pixels, %.1f ms", rs_.width, rs_.height,
                  (unsigned long long)S.fragments, (unsigned long long)S.rendered_pixels, total_ms);
    std::string out = line;
    // The scalar a reader chose itself because its default was constant.
    if (!in_.mesh.scalar_choice.empty())
      out += "; scalar '" + in_.mesh.scalar_name + "' (" + in_.mesh.scalar_choice + ")";
    return out + left_out_note({{nonfinite_tets_, "tet with a non-finite coordinate or scalar",
                                 "tets with a non-finite coordinate or scalar"}});
  }
  std::string empty_reason(const TiledRenderer& r) const override;

 private:
  static const ZSweepRenderer& of(const TiledRenderer& r) { return static_cast<const ZSweepRenderer&>(r); }
  SceneInput& in_;
  RenderSettings rs_;  // outlives every renderer made from it
  Topology topo_;
  // The per-view arrays, reused by every frame (render_frames drops one
  // renderer before it makes the next).
  ViewBuffers buffers_;
  double ms_topology_ = 0;
  VolumeMemory held_;
  uint64_t nonfinite_tets_ = 0;
};

nlohmann::json VolumeJob::stats(const TiledRenderer& r, const FrameReport& f) const {
  RenderStats S = of(r).stats();
  S.peak_rss_bytes = std::max(S.peak_rss_bytes, f.peak_rss ? f.peak_rss : peak_rss_bytes());
  S.ms_total = frame_total(S.ms_total, S.ms_setup, f);
  const Scene& scene = in_.scene;
  const TetMesh& m = in_.mesh;
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
        {"load", in_.ms_load},
        {"topology", ms_topology_}}},
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
      {"cell_data_tets", S.cell_data_tets},
      {"tets_clipped", S.tets_clipped},
      {"segments_clipped", S.segments_clipped},
      {"rays_stopped_by_geometry", S.rays_stopped},
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
      {"mesh",
       {{"points", m.num_points()},
        {"tets", m.num_tets()},
        {"tets_nonfinite", nonfinite_tets_},  // left out of the render
        {"scalar", m.scalar_name},
        {"association", m.has_cell_scalars() ? "cell" : m.has_scalars() ? "point" : "none"},
        {"scalar_choice", m.scalar_choice}}},  // why the reader chose it ("" when it was its default or named)
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
  if (f.frame_ms.size() > 1) j["frame_ms"] = f.frame_ms;
  return j;
}

std::string VolumeJob::empty_reason(const TiledRenderer& r) const {
  const RenderStats st = of(r).stats();
  if (st.rendered_pixels > 0) return "";
  const View view(rs_.camera, rs_.width, rs_.height);
  bool in_front = false, any_depth = false;
  for (const glm::dvec3& p : in_.mesh.points) {
    const double z = view.project(p).z;
    any_depth |= std::isfinite(z);
    in_front |= z > 0;
  }
  const size_t tets = in_.mesh.num_tets();
  return !any_depth ? "the camera cannot resolve the mesh at this scale (depths are not finite)"
         : !in_front                                      ? "the whole mesh is behind the camera"
         : nonfinite_tets_ == tets                          ? "every tet has a non-finite coordinate or scalar"
         : st.tets_clipped >= tets                        ? "the clip planes keep none of the mesh"
         : st.tets_invisible + st.tets_degenerate >= tets ? "the transfer function's opacity is zero "
                                                             "wherever the mesh is (or its cells are flat)"
         : st.faces_projected == 0                        ? "the mesh is outside the view"
                                                           : "no fragment reached a pixel";
}

}  // namespace

std::unique_ptr<SceneJob> make_volume_job(SceneInput& in) { return std::make_unique<VolumeJob>(in); }

}  // namespace zs
