// Sphere scenes: the sphere-sprite renderer (src/render/spheres/), its colours,
// grid and AO maps made once and shared by every frame.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "app/scene_jobs.h"
#include "geometry/spheres/sphere_colors.h"
#include "render/spheres/sphere_ao.h"
#include "render/spheres/sphere_renderer.h"
#include "base/util/memory.h"

namespace zs {

namespace {

class SphereJob : public SceneJob {
 public:
  SphereJob(SceneInput& in, bool no_culling) : in_(in) {
    SphereScene& sp = in.scene.spheres;
    if (no_culling) sp.culling = false;
    const RenderSettings& rs = in.scene.settings;
    srs_ = sphere_render_settings(rs, sp);
    color_ = sp.has_color_mode ? sp.color : default_color_mode(in.spheres);
    try {
      colors_ = sphere_colors(in.spheres, color_, rs.tf);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(sp.path + ": " + e.what());
    }
    const auto t0 = std::chrono::steady_clock::now();
    sgrid_ = build_sphere_grid(in.spheres, srs_.grid);
    ms_grid_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    grid_ = TileGrid{rs.width, rs.height, rs.tile_size, sphere_channels(srs_)};
    if (srs_.ao.directions) names_ = {"R", "G", "B", "A", "Z", "AO"};
    held_ = sphere_set_bytes(in.spheres) + colors_.size() * sizeof(glm::vec4);
    // AO maps: built once for the set and shared by every frame (they do not
    // depend on the view), when they fit the budget; else every frame builds
    // and consumes them in batches (the renderer says when it cannot).
    if (srs_.ao.directions) {
      const uint64_t budget = srs_.budget();
      ao_ = sphere_ao_maps(in.spheres, colors_, srs_, budget > held_ ? budget - held_ : 0);
      if (!ao_) srs_.ao.batches = true;
    }
  }
  std::unique_ptr<TiledRenderer> renderer(uint64_t extra_bytes, bool progress) override {
    srs_.progress = progress;
    auto r = std::make_unique<SphereRenderer>(in_.spheres, colors_, sgrid_, srs_, held_ + extra_bytes, ao_);
    if (ao_ && r->stats().ao_batches) {  // the maps left no room for the frame: batches from now on
      ao_.reset();
      srs_.ao.batches = true;
    }
    return r;
  }
  double total_ms(const TiledRenderer& r) const override { return of(r).stats().ms_total; }
  nlohmann::json stats(const TiledRenderer& r, const FrameReport& f) const override;
  std::string summary(const TiledRenderer& r, double total_ms) const override {
    const SphereStats st = of(r).stats();
    char line[256];
    std::snprintf(line, sizeof line, "%ux%u, %llu spheres drawn of %llu, %llu rendered pixels, %.1f ms",
                  in_.scene.settings.width, in_.scene.settings.height, (unsigned long long)st.vis.spheres_visible,
                  (unsigned long long)st.spheres, (unsigned long long)st.rendered_pixels, total_ms);
    // Invalid records the reader dropped and invalid spheres of data given as arrays.
    return line + left_out_note({{in_.spheres.invalid + st.invalid,
                                  "sphere with a non-finite centre or a zero, negative or non-finite radius",
                                  "spheres with a non-finite centre or a zero, negative or non-finite radius"},
                                 {in_.spheres.skipped, "PDB alternate location", "PDB alternate locations"}});
  }
  std::string empty_reason(const TiledRenderer& r) const override {
    return of(r).stats().rendered_pixels ? "" : "no sphere is in front of the camera and in view";
  }

 private:
  static const SphereRenderer& of(const TiledRenderer& r) { return static_cast<const SphereRenderer&>(r); }
  SceneInput& in_;
  SphereRenderSettings srs_;
  SphereColorMode color_;
  std::vector<glm::vec4> colors_;
  SphereGrid sgrid_;
  double ms_grid_ = 0;
  uint64_t held_ = 0;
  std::shared_ptr<const SphereAoMaps> ao_;
};

nlohmann::json SphereJob::stats(const TiledRenderer& r, const FrameReport& f) const {
  SphereStats S = of(r).stats();
  S.ms_grid = ms_grid_;
  if (ao_) S.ms_ao_maps = ao_->ms_build;
  S.ms_total = frame_total(S.ms_total, S.ms_setup, f);
  if (f.peak_rss) S.peak_rss_bytes = std::max(S.peak_rss_bytes, f.peak_rss);
  const SceneInput& in = in_;
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
      {"color", to_string(color_)},
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
  if (f.frame_ms.size() > 1) j["frame_ms"] = f.frame_ms;
  return j;
}

}  // namespace

std::unique_ptr<SceneJob> make_sphere_job(SceneInput& in, bool no_culling) {
  return std::make_unique<SphereJob>(in, no_culling);
}

}  // namespace zs
