// The ZSweep engine (B-Convert digest §1): sweep a plane through the vertices in depth
// order, project the not-yet-projected faces of each swept vertex's use set
// into per-pixel fragment lists, and composite lazily — a fragment is
// composited once the sweep has passed it, so every fragment is final when it
// is consumed (delayed compositing).
//
// The image is cut into square screen tiles. The sweep order of the faces is
// computed once for the whole mesh (the vertex heap), faces are binned to the
// tiles their screen boxes touch, and each tile is swept on its own over its
// bin, in that global order: a tile's pixel state and fragment pool stay in
// cache, tiles run on any number of threads (or MPI ranks), and every pixel
// sees the same fragments in the same order whatever the tiling, so images
// are bit-identical for any thread count and tile size.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "raster/image.h"
#include "raster/tiled_renderer.h"
#include "render/volume/opaque_layer.h"
#include "render/volume/render_plan.h"
#include "render/volume/render_settings.h"
#include "render/volume/render_stats.h"
#include "render/volume/view_buffers.h"

namespace zs {

// A render prepared once (mesh -> view -> classes -> sweep order -> tile
// bins) and swept tile by tile. Construction throws std::runtime_error when
// the memory budget cannot hold the shared state and one tile per thread;
// render_tiles throws when the fragments that must be pending at once in a
// tile do not fit.
class ZSweepRenderer : public TiledRenderer {
 public:
  // `sink_bytes`: what the caller's sink holds, counted against the budget.
  // `reuse`: per-view arrays a previous renderer of this mesh gave back (or
  // empty ones); this one takes them and gives its own back when destroyed.
  ZSweepRenderer(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, uint64_t sink_bytes = 0,
                 ViewBuffers* reuse = nullptr);
  ~ZSweepRenderer() override;
  ZSweepRenderer(const ZSweepRenderer&) = delete;
  ZSweepRenderer& operator=(const ZSweepRenderer&) = delete;

  const TileGrid& grid() const override;
  int threads() const override;
  // Sweeps the given tiles (ids into grid(); all when null) on
  // settings.threads threads and hands each to the sink. Adds this call's
  // per-tile counts (and its wall time to ms_total) to `stats`.
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles, RenderStats* stats);
  // TiledRenderer: the same, into the renderer's own running tile totals.
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) override;
  std::vector<uint8_t> tile_totals() const override;
  void add_tile_totals(const std::vector<uint8_t>& other) override;

  // Mixed scenes: the opaque geometry under the volume for the following
  // render_tiles calls (null: none, the background); it must outlive them.
  void set_opaque_layer(const OpaqueLayer* layer);

  // Setup counts and times (classification, order, bins, plan).
  const RenderStats& setup_stats() const;
  // Setup plus the running tile totals: ms_total = setup + the wall time of
  // the render_tiles calls into the totals.
  RenderStats stats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Every tile into `sink`.
void render_zsweep_tiles(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, TileSink& sink,
                         uint64_t sink_bytes, RenderStats* stats);
// The whole image in memory.
Image render_zsweep(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, RenderStats* stats);

}  // namespace zs
