// The surface renderer (docs/shadows.md): a z-buffer renderer of triangle
// meshes with shadows, on the raster core, tile loop, threads, tiled writers
// and MPI of the other renderers. Its tiles carry premultiplied R, G, B, A,
// the view depth Z of the nearest surface (+inf where none) and, per light,
// the fraction of that light reaching the visible point before shading
// (`lit0`, `lit1`, ...; +inf where no surface).
//
// Set-up per frame: the triangles are projected into the camera (back-face
// and view-volume culling, near clipping: lighting/triangle_projection.h)
// and binned to tiles; each light gets its shadow map (lighting/shadow_map.h,
// orthographic maps fitted to the receivers in view), or, with shadows.mode
// exact, one Embree BVH answers shadow rays. A tile z-buffers its triangles
// (raster/zbuffer_tile.h), then resolves each covered pixel once: the exact
// hit of the pixel's ray with the winning triangle's plane, its normal, the
// shadow tests and the shading (deferred: cost follows pixels, not overdraw).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raster/tiled_renderer.h"
#include "render/surfaces/surface_settings.h"
#include "render/surfaces/surface_stats.h"
#include "geometry/triangles/triangle_mesh.h"

namespace zs {

class SurfaceRenderer : public TiledRenderer {
 public:
  // `mesh` needs its point normals (compute_point_normals). `extra_bytes`:
  // what the caller holds besides, counted against the memory budget.
  // Throws std::runtime_error when the budget cannot hold the render.
  SurfaceRenderer(const TriangleMesh& mesh, const SurfaceRenderSettings& settings, uint64_t extra_bytes = 0);
  ~SurfaceRenderer() override;
  const TileGrid& grid() const override;  // RGBA, Z, lit per light
  int threads() const override;
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) override;
  std::vector<uint8_t> tile_totals() const override;
  void add_tile_totals(const std::vector<uint8_t>& other) override;
  SurfaceStats stats() const;
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// The channel names of a surface render with `lights` lights.
std::vector<std::string> surface_channel_names(size_t lights);

// Bytes a mesh holds (points, triangles, normals), for budgets.
uint64_t triangle_mesh_bytes(const TriangleMesh& m);

}  // namespace zs
