// Surface scenes: the z-buffer surface renderer with shadows (src/render/surfaces/).
#include <algorithm>
#include <cstdio>
#include <string>

#include "app/scene_jobs.h"
#include "render/surfaces/surface_renderer.h"

namespace zs {

namespace {

class SurfaceJob : public SceneJob {
 public:
  explicit SurfaceJob(SceneInput& in)
      : in_(in), rs_(surface_render_settings(in.scene.settings, in.scene.surfaces)), held_(triangle_mesh_bytes(in.surface)) {
    grid_ = TileGrid{rs_.width, rs_.height, rs_.tile_size, uint32_t(5 + rs_.lights.size())};
    names_ = surface_channel_names(rs_.lights.size());
  }
  void keep_rgba_only() override {
    rs_.depth_and_lit = false;
    grid_.channels = 4;
    names_ = {"R", "G", "B", "A"};
  }
  std::unique_ptr<TiledRenderer> renderer(uint64_t extra_bytes, bool progress) override {
    rs_.progress = progress;
    return std::make_unique<SurfaceRenderer>(in_.surface, rs_, held_ + extra_bytes);
  }
  double total_ms(const TiledRenderer& r) const override { return of(r).stats().ms_total; }
  nlohmann::json stats(const TiledRenderer& r, const FrameReport& f) const override;
  std::string summary(const TiledRenderer& r, double total_ms) const override {
    const SurfaceStats st = of(r).stats();
    const size_t lights = rs_.lights.size();
    char line[256];
    std::snprintf(line, sizeof line, "%ux%u, %llu of %llu triangles drawn, %llu rendered pixels, %zu light%s, %.1f ms",
                  rs_.width, rs_.height,
                  (unsigned long long)(st.project.triangles - st.project.back_culled - st.project.view_culled -
                                       st.project.degenerate),
                  (unsigned long long)st.project.triangles, (unsigned long long)st.tiles.rendered_pixels, lights,
                  lights == 1 ? "" : "s", total_ms);
    std::string out = line;
    // What loading changed, so an image that differs from the file's own
    // winding or the ground's usual place is never a surprise.
    const size_t turned = in_.surface_solids.inward;
    if (turned)
      out += ", " + std::to_string(turned) + " closed surface" + (turned == 1 ? "" : "s") +
             " wound inward turned outward";
    if (in_.ground_lowered_by > 0) {
      std::snprintf(line, sizeof line,
                    ", ground lowered %.3g below the mesh's lowest y (a level face there would fight it)",
                    in_.ground_lowered_by);
      out += line;
    }
    return out + left_out_note({{in_.surface_elements_dropped, "element with fewer than three corners (a line or point)",
                                  "elements with fewer than three corners (lines or points)"}});
  }
  std::string empty_reason(const TiledRenderer& r) const override {
    return of(r).stats().tiles.rendered_pixels ? "" : "no triangle is in front of the camera and in view";
  }
  // The shadow maps' buffers: with the previous frame's still held while the
  // next is made, they come back from the heap instead of being faulted in
  // anew (a 1024² frame of tests/data/surfaces/pyramid.obj: 24 ms instead of
  // 44-58 ms, the shadow set-up 2 ms instead of 21-28 ms).
  bool overlap_frames() const override { return true; }

 private:
  static const SurfaceRenderer& of(const TiledRenderer& r) { return static_cast<const SurfaceRenderer&>(r); }
  SceneInput& in_;
  SurfaceRenderSettings rs_;
  uint64_t held_;
};

nlohmann::json SurfaceJob::stats(const TiledRenderer& r, const FrameReport& f) const {
  SurfaceStats S = of(r).stats();
  S.ms_total = frame_total(S.ms_total, S.ms_setup, f);
  if (f.peak_rss) S.peak_rss_bytes = std::max(S.peak_rss_bytes, f.peak_rss);
  const SurfaceTileTotals& T = S.tiles;
  const SceneInput& in = in_;
  const SurfaceRenderSettings& rs = rs_;
  nlohmann::json maps = nlohmann::json::array();
  for (const ShadowMapStats& m : S.maps)
    maps.push_back({{"project_ms", m.ms_project},
                    {"raster_ms", m.ms_raster},
                    {"multi_depth_ms", m.ms_multi_depth},
                    {"casters", m.casters},
                    {"casters_culled", m.casters_culled},
                    {"casters_back_faces", m.casters_back_faces},
                    {"caster_fragments", m.caster_fragments},
                    {"texels_covered", m.texels_covered},
                    {"bytes", m.bytes},
                    {"texel", m.texel},
                    {"side", m.side}});
  const ShadowSettings& sh = rs.shadows;
  const size_t two_sided = size_t(std::count(in.surface.two_sided.begin(), in.surface.two_sided.end(), uint8_t(1)));
  nlohmann::json j = {
      {"renderer", "surfaces"},
      {"time_ms",
       {{"total", S.ms_total},
        {"setup", S.ms_setup},
        {"project", S.ms_project},
        {"binning", S.ms_binning},
        {"shadows", S.ms_shadows},
        {"light_fit", S.ms_fit},
        {"rays_build", S.ms_rays_build},
        {"tiles_all_threads", T.ms_tiles},
        {"load", in.ms_load}}},
      {"triangles",
       {{"total", S.project.triangles},
        {"back_face_culled", S.project.back_culled},
        {"view_culled", S.project.view_culled},
        {"near_clipped", S.project.near_clipped},
        {"degenerate", S.project.degenerate},
        {"back_faces_two_sided", S.project.back_two_sided},
        {"polygons_split_on_read", in.surface_polygons_split},
        {"elements_dropped_on_read", in.surface_elements_dropped}}},
      {"culling", {{"back_face", rs.cull_back}, {"view", rs.cull_view}}},
      // Closed solids are one-sided (wound inward: turned outward at load);
      // open surfaces are two-sided, never back-face culled.
      {"orientation",
       {{"components", in.surface_solids.components},
        {"closed_solids", in.surface_solids.closed},
        {"turned_outward", in.surface_solids.inward},
        {"two_sided_triangles", two_sided}}},
      {"ground",
       {{"enabled", in.scene.surfaces.ground},
        {"height", in.scene.surfaces.ground_height},
        {"lowered_by", in.ground_lowered_by}}},
      {"bin_entries", S.bin_entries},
      {"triangles_scanned", T.triangles_scanned},
      {"fragments", T.fragments},
      {"depth_writes", T.depth_writes},
      {"rendered_pixels", T.rendered_pixels},
      {"lights", rs.lights.size()},
      {"shadows",
       {{"enabled", rs.shadows_enabled},
        {"mode", to_string(sh.mode)},
        {"map_size", sh.map_size},
        {"depths", sh.depths},
        {"select", to_string(sh.select)},
        {"pcf", sh.pcf},
        {"bias", sh.bias},
        {"slope_bias", sh.slope_bias},
        {"levels", sh.depths * sh.pcf + 1},
        {"tests", T.shadow_tests},
        // Tests decided by map tiles with no caster (no depth read).
        {"tests_in_empty_tiles", T.shadow_tests_empty},
        {"depth_reads", (T.shadow_tests - T.shadow_tests_empty) * sh.depths * sh.pcf},
        {"rays", T.shadow_rays},
        {"lit_pixel_lights", T.lit_pixels},
        {"maps", maps}}},
      {"tiles", T.tiles},
      {"tile_size", S.tile_size},
      {"image", {{"width", rs.width}, {"height", rs.height}}},
      {"peak_rss_bytes", S.peak_rss_bytes},
      {"memory_budget_bytes", S.memory_budget_bytes},
  };
  if (f.frame_ms.size() > 1) j["frame_ms"] = f.frame_ms;
  return j;
}

}  // namespace

std::unique_ptr<SceneJob> make_surface_job(SceneInput& in) { return std::make_unique<SurfaceJob>(in); }

}  // namespace zs
