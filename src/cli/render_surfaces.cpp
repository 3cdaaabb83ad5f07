#include "cli/render_surfaces.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/json_out.h"
#include "cli/render_mpi.h"
#include "image/tile_writer.h"
#include "surface/surface_renderer.h"

namespace zs {

namespace {

void write_surface_stats(const std::string& path, const SurfaceStats& S, const SceneInput& in,
                         const SurfaceRenderSettings& rs, const std::vector<double>& frame_ms) {
  const SurfaceTileTotals& T = S.tiles;
  nlohmann::json maps = nlohmann::json::array();
  for (const ShadowMapStats& m : S.maps)
    maps.push_back({{"project_ms", m.ms_project},
                    {"raster_ms", m.ms_raster},
                    {"multi_depth_ms", m.ms_multi_depth},
                    {"casters", m.casters},
                    {"casters_culled", m.casters_culled},
                    {"caster_fragments", m.caster_fragments},
                    {"texels_covered", m.texels_covered},
                    {"bytes", m.bytes},
                    {"texel", m.texel},
                    {"side", m.side}});
  const ShadowSettings& sh = rs.shadows;
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
        {"polygons_split_on_read", in.surface_polygons_split},
        {"elements_dropped_on_read", in.surface_elements_dropped}}},
      {"culling", {{"back_face", rs.cull_back}, {"view", rs.cull_view}}},
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
        {"depth_reads", T.shadow_tests * sh.depths * sh.pcf},
        {"rays", T.shadow_rays},
        {"lit_pixel_lights", T.lit_pixels},
        {"maps", maps}}},
      {"tiles", T.tiles},
      {"tile_size", S.tile_size},
      {"image", {{"width", rs.width}, {"height", rs.height}}},
      {"peak_rss_bytes", S.peak_rss_bytes},
      {"memory_budget_bytes", S.memory_budget_bytes},
  };
  if (frame_ms.size() > 1) j["frame_ms"] = frame_ms;
  write_json_file(path, j);
}

void print_line(const std::string& out_path, const SurfaceRenderSettings& rs, const SurfaceStats& st) {
  std::printf("wrote %s: %ux%u, %llu of %llu triangles drawn, %llu rendered pixels, %zu light%s, %.1f ms\n",
              out_path.c_str(), rs.width, rs.height,
              (unsigned long long)(st.project.triangles - st.project.back_culled - st.project.view_culled -
                                   st.project.degenerate),
              (unsigned long long)st.project.triangles, (unsigned long long)st.tiles.rendered_pixels, rs.lights.size(),
              rs.lights.size() == 1 ? "" : "s", st.ms_total);
}

}  // namespace

void run_surfaces(SceneInput& in, const std::string& out_path, const std::string& stats_path, int frames,
                  const std::string& compression) {
  const SurfaceRenderSettings rs = surface_render_settings(in.scene.settings, in.scene.surfaces);
  const TileGrid grid{rs.width, rs.height, rs.tile_size, uint32_t(5 + rs.lights.size())};
  const std::vector<std::string> names = surface_channel_names(rs.lights.size());
  const uint64_t held = triangle_mesh_bytes(in.surface);
  if (render_mpi_enabled()) {
    std::unique_ptr<ImageTileWriter> w;
    if (render_mpi_rank() == 0) w = std::make_unique<ImageTileWriter>(out_path, grid, compression, names);
    SurfaceRenderer r(in.surface, rs,
                      held + (w ? w->buffer_bytes_estimate() : 0) + render_mpi_message_bytes(grid, rs.threads));
    MpiReport report;
    render_mpi(r, w.get(), &report);
    if (!w) return;
    w->commit();
    SurfaceStats st = r.stats();
    st.ms_total = st.ms_setup + report.wall_ms;
    for (uint64_t p : report.peak_rss) st.peak_rss_bytes = std::max(st.peak_rss_bytes, p);
    if (!stats_path.empty()) write_surface_stats(stats_path, st, in, rs, {});
    print_line(out_path, rs, st);
    return;
  }
  ImageTileWriter writer(out_path, grid, compression, names);
  struct Discard : TileSink {
    void tile(const TileRect&, const float*) override {}
  } discard;
  std::vector<double> frame_ms;
  std::unique_ptr<SurfaceRenderer> r;
  for (int f = 0; f < frames; ++f) {
    r = std::make_unique<SurfaceRenderer>(in.surface, rs, held + writer.buffer_bytes_estimate());
    if (f + 1 < frames) {
      r->render_tiles(discard, nullptr);
    } else {
      r->render_tiles(writer, nullptr);
      writer.commit();
    }
    frame_ms.push_back(r->stats().ms_total);
  }
  SurfaceStats st = r->stats();
  if (frames > 1) st.ms_total = *std::min_element(frame_ms.begin(), frame_ms.end());
  if (st.tiles.rendered_pixels == 0)
    std::fprintf(stderr, "zsweep: warning: %s: the image is empty: no triangle is in front of the camera and in view\n",
                 out_path.c_str());
  if (!stats_path.empty()) write_surface_stats(stats_path, st, in, rs, frame_ms);
  print_line(out_path, rs, st);
}

}  // namespace zs
