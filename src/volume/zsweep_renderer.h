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
  uint64_t pixel_tests = 0, pixel_hits = 0, fragments = 0, rendered_pixels = 0;
  uint64_t faces_projected = 0, faces_culled = 0, faces_offscreen = 0, faces_degenerate = 0, faces_clipped = 0;
  uint64_t tets_invisible = 0, tets_degenerate = 0;
  uint64_t max_list_length = 0, forced_composites = 0, budget_flushes = 0;
  uint64_t composite_events = 0, segments = 0, early_terminated_pixels = 0;
  uint64_t peak_fragments = 0, peak_rss_bytes = 0, memory_budget_bytes = 0;
  uint64_t bconvert_fallbacks = 0;  // faces too large for B-Convert, scanned by bounding box
  uint64_t row_end_misses[4] = {0, 0, 0, 0};  // B-Convert rows ends with 0, 1, 2, 3+ false pixels
  double face_area = 0, bbox_area = 0;        // summed over projected faces, in pixels (Table 4.4)
};

// Throws std::runtime_error when the memory budget cannot hold the image state
// or the fragments that must be pending at once.
Image render_zsweep(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, RenderStats* stats);

uint64_t default_memory_budget();
// Bytes the engine needs before any fragment: per-pixel state and per-vertex
// and per-face arrays. The rest of the budget holds 16-byte fragments.
uint64_t zsweep_state_bytes(size_t num_points, size_t num_faces, uint32_t width, uint32_t height);
uint64_t peak_rss_bytes();

}  // namespace zs
