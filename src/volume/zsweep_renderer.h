// The ZSweep engine (digest §1): sweep a plane through the vertices in depth
// order, project the not-yet-projected faces of each swept vertex's use set
// into per-pixel fragment lists, and composite lazily — when the sweep passes
// z_target, the farthest vertex of the faces projected so far, every pending
// fragment is final and is composited (delayed compositing).
#pragma once

#include <cstddef>
#include <cstdint>

#include "image/image.h"
#include "mesh/tet_mesh.h"
#include "mesh/topology.h"
#include "volume/render_settings.h"

namespace zs {

struct RenderStats {
  double ms_total = 0, ms_setup = 0, ms_list_generation = 0, ms_scan_convert = 0, ms_insert = 0, ms_composite = 0;
  uint64_t pixel_tests = 0, pixel_hits = 0, pixel_misses = 0, fragments = 0, rendered_pixels = 0;
  uint64_t faces_projected = 0, faces_culled = 0, faces_offscreen = 0, faces_degenerate = 0, faces_clipped = 0;
  uint64_t tets_invisible = 0, tets_degenerate = 0;
  uint64_t max_list_length = 0, forced_composites = 0, budget_flushes = 0;
  uint64_t composite_events = 0, segments = 0, early_terminated_pixels = 0;
  uint64_t peak_fragments = 0, peak_rss_bytes = 0, memory_budget_bytes = 0;
  uint64_t bands = 0, fragment_capacity = 0;  // the BandPlan used
  uint64_t bconvert_fallbacks = 0;  // faces too large for B-Convert, scanned by bounding box
  uint64_t row_end_misses[4] = {0, 0, 0, 0};  // B-Convert rows ends with 0, 1, 2, 3+ false pixels
  double face_area = 0, bbox_area = 0;        // summed over projected faces, in pixels (Table 4.4)
};

// Receives finished row bands [y0, y1) of premultiplied RGBA floats (width·4
// per row). Bands arrive in any order; calls are serialized.
class BandSink {
 public:
  virtual ~BandSink() = default;
  virtual void band(uint32_t y0, uint32_t y1, const float* rgba) = 0;
};

// The image is swept in row bands: as many as the threads want, and more when
// the memory budget cannot hold the whole image's per-pixel state at once
// (bands then run in turn). `sink_bytes` is what the sink itself holds, counted
// against the budget. Throws std::runtime_error when the budget cannot hold the
// state or the fragments that must be pending at once.
void render_zsweep_bands(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, BandSink& sink,
                         uint64_t sink_bytes, RenderStats* stats);
// The whole image in memory.
Image render_zsweep(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, RenderStats* stats);

uint64_t default_memory_budget();
// Per-pixel bytes of a band in flight (compositor, list heads, band buffer),
// and the shared per-vertex/per-face bytes. The rest of the budget holds
// 16-byte fragments.
constexpr uint64_t kBytesPerPixel = 3 * 8 + 8 + 4 + 4 + 4 + 1 + 4 * 3 + 1 + 16;
uint64_t zsweep_shared_bytes(size_t num_points, size_t num_faces);

// How a render is split to fit its budget: shared state first, then per
// running band its pixels' state (at most half of what is left, split between
// the threads), fragments get the rest. Throws when nothing fits.
struct BandPlan {
  uint64_t bands = 1, band_rows = 0, max_fragments = 0;  // max_fragments per running band
};
BandPlan plan_bands(uint64_t budget, size_t num_points, size_t num_faces, uint32_t width, uint32_t height,
                    int threads, uint64_t sink_bytes);
uint64_t peak_rss_bytes();

}  // namespace zs
