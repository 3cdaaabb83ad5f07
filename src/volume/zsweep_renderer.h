// The ZSweep engine (digest §1): sweep a plane through the vertices in depth
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

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "image/image.h"
#include "mesh/tet_mesh.h"
#include "mesh/topology.h"
#include "volume/render_settings.h"

namespace zs {

struct RenderStats {
  double ms_total = 0, ms_setup = 0, ms_list_generation = 0, ms_scan_convert = 0, ms_insert = 0, ms_composite = 0;
  double ms_order = 0, ms_binning = 0;  // parts of setup: the heap's face order, the tile bins
  uint64_t pixel_tests = 0, pixel_hits = 0, pixel_misses = 0, fragments = 0, rendered_pixels = 0;
  uint64_t faces_projected = 0, faces_culled = 0, faces_offscreen = 0, faces_degenerate = 0, faces_clipped = 0;
  uint64_t tets_invisible = 0, tets_degenerate = 0;
  uint64_t max_list_length = 0, forced_composites = 0, budget_flushes = 0;
  uint64_t composite_events = 0, segments = 0, early_terminated_pixels = 0;
  uint64_t peak_fragments = 0, peak_rss_bytes = 0, memory_budget_bytes = 0;
  uint64_t peak_overflow_fragments = 0;  // of peak_fragments, the most beyond the records' inline slots
  uint64_t tiles = 0, tile_size = 0, bin_entries = 0;  // the plan used
  uint64_t fragment_capacity = 0;  // overflow fragments per thread the budget allows
  uint64_t bconvert_fallbacks = 0;  // faces too large for B-Convert, scanned by bounding box
  uint64_t row_end_misses[4] = {0, 0, 0, 0};  // B-Convert rows ends with 0, 1, 2, 3+ false pixels
  double face_area = 0, bbox_area = 0;        // summed over projected faces, in pixels (Table 4.4)
};
void add_stats(RenderStats& into, const RenderStats& tile);  // sums the per-tile parts

// Columns [x0, x1), rows [y0, y1) of the image.
struct TileRect {
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  uint32_t width() const { return x1 - x0; }
  uint32_t height() const { return y1 - y0; }
};

// Square tiles of `size` pixels, row-major from the top left; the last
// column and row may be narrower.
struct TileGrid {
  uint32_t width = 0, height = 0, size = 64;
  uint32_t cols() const { return (width + size - 1) / size; }
  uint32_t rows() const { return (height + size - 1) / size; }
  uint32_t count() const { return cols() * rows(); }
  TileRect rect(uint32_t tile) const;
};

// Receives finished tiles: width·height premultiplied RGBA floats, row-major.
// Calls are serialized; tiles arrive in any order (roughly row-major).
class TileSink {
 public:
  virtual ~TileSink() = default;
  virtual void tile(const TileRect& r, const float* rgba) = 0;
};

// A render prepared once (mesh -> view -> classes -> sweep order -> tile
// bins) and swept tile by tile. Construction throws std::runtime_error when
// the memory budget cannot hold the shared state and one tile per thread;
// render_tiles throws when the fragments that must be pending at once in a
// tile do not fit.
class ZSweepRenderer {
 public:
  // `sink_bytes`: what the caller's sink holds, counted against the budget.
  ZSweepRenderer(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, uint64_t sink_bytes = 0);
  ~ZSweepRenderer();
  ZSweepRenderer(const ZSweepRenderer&) = delete;
  ZSweepRenderer& operator=(const ZSweepRenderer&) = delete;

  const TileGrid& grid() const;
  // Sweeps the given tiles (ids into grid(); all when null) on
  // settings.threads threads and hands each to the sink. Adds this call's
  // per-tile counts to `stats` (setup counts are filled by the constructor).
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles, RenderStats* stats);
  // Setup counts and times (classification, order, bins, plan).
  const RenderStats& setup_stats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Every tile into `sink`.
void render_zsweep_tiles(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, TileSink& sink,
                         uint64_t sink_bytes, RenderStats* stats);
// The whole image in memory.
Image render_zsweep(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, RenderStats* stats);

// Throws the error a render would throw at set-up when the memory budget
// (settings.memory_budget_bytes, 0: default) cannot hold it, before anything
// large is allocated, for callers that open their sink (sink_bytes) only
// afterwards. Returns the shared bytes known so far.
uint64_t check_memory_budget(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings,
                             uint64_t sink_bytes);
uint64_t default_memory_budget();
uint64_t peak_rss_bytes();

// Per-pixel bytes of a tile in flight (pixel record, with its first
// kInline fragments, its accumulators and its output), the bytes the plan charges per vertex,
// face and bin entry; overflow fragments are 16 bytes.
constexpr uint64_t kTilePixelBytes = 64 + 32 + 16;
uint64_t zsweep_shared_bytes(size_t num_points, size_t num_faces);

// How a render fits its budget: shared state (vertices, faces, bins, sink),
// then per thread one tile's pixel state; the fragment pools get the rest.
struct RenderPlan {
  uint64_t shared_bytes = 0, max_fragments = 0;  // max_fragments per thread's pool
};
RenderPlan plan_render(uint64_t budget, uint64_t shared_bytes, uint32_t tile_size, int threads);

}  // namespace zs
