// The sphere-sprite renderer (spheres digest §2.1–2.2): every sphere is an
// exact impostor. Opaque here; the translucent modes resolve tiles with
// translucent_tile.h on the same visibility and bins. Its silhouette is
// scanned as one exact conic span per row (raster/sphere_span.h); each covered pixel's depth is the exact entry of
// the pixel's ray into the sphere (its exit when the eye is inside), so
// interpenetrating spheres meet on their true intersection curve in both
// projections. A tile keeps the nearest (depth, sphere id) per pixel — ties
// to the smaller id, so the image never depends on the order of spheres,
// tiles, threads or culling — and then shades each pixel once from its
// winner's exact normal (deferred: shading cost follows visible pixels, not
// overdraw).
//
// Set-up per frame, step by step: the settings checked, the memory the frame
// holds counted against the budget (base/util/memory_ledger.h), the AO maps
// (all held, or built in batches by every frame), the visibility tests
// (sphere_visibility.h), then the visible spheres binned nearest first to
// the tiles their silhouette boxes touch (sphere_bins.h).
#pragma once

#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/tiled_renderer.h"
#include "lighting/sphere_map.h"
#include "geometry/spheres/sphere_set.h"
#include "render/spheres/sphere_grid.h"
#include "render/spheres/sphere_settings.h"
#include "render/spheres/sphere_stats.h"

namespace zs {

class SphereRenderer : public TiledRenderer {
 public:
  // `colors`: one RGBA per sphere (geometry/spheres/sphere_colors.h); `grid`: built
  // from `spheres` with settings.grid cells per axis (kept by the caller
  // across frames: the data are static). `extra_bytes`: what the caller holds
  // besides (the set, its sink), counted against the memory budget. Throws
  // std::runtime_error when the budget cannot hold the render.
  // `ao_maps`: the set's AO maps when settings.ao is on and the caller keeps
  // them across frames (sphere_ao_maps()); null: built here when they fit the
  // budget (and settings.ao.batches is off), else built and consumed in
  // batches by every render_tiles().
  SphereRenderer(const SphereSet& spheres, const std::vector<glm::vec4>& colors, const SphereGrid& grid,
                 const SphereRenderSettings& settings, uint64_t extra_bytes = 0,
                 std::shared_ptr<const SphereAoMaps> ao_maps = nullptr);
  ~SphereRenderer() override;

  const TileGrid& grid() const override;  // RGBA + Z
  int threads() const override;
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) override;
  std::vector<uint8_t> tile_totals() const override;
  void add_tile_totals(const std::vector<uint8_t>& other) override;

  // Setup plus the running tile totals (ms_total: setup + render_tiles time).
  SphereStats stats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Bytes the set itself holds (centres, radii, scalars, colours), for budgets.
uint64_t sphere_set_bytes(const SphereSet& s);
// Channels of a tile: R, G, B, A, Z, then AO when ambient occlusion is on.
uint32_t sphere_channels(const SphereRenderSettings& rs);

}  // namespace zs
