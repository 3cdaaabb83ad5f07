// What a ZSweep render counts and times (`render --stats`, docs/scene.md).
#pragma once

#include <cstdint>

namespace zs {

struct RenderStats {
  double ms_total = 0, ms_setup = 0, ms_list_generation = 0, ms_scan_convert = 0, ms_insert = 0, ms_composite = 0;
  double ms_order = 0, ms_binning = 0;  // parts of setup: the heap's face order, the tile bins
  uint64_t pixel_tests = 0, pixel_hits = 0, pixel_misses = 0, fragments = 0, rendered_pixels = 0;
  uint64_t faces_projected = 0, faces_culled = 0, faces_offscreen = 0, faces_degenerate = 0, faces_clipped = 0;
  uint64_t tets_invisible = 0, tets_degenerate = 0;
  uint64_t cell_data_tets = 0;  // visible tets carrying one (cell) value each
  uint64_t tets_clipped = 0;    // wholly outside a clip plane (not projected)
  uint64_t segments_clipped = 0;  // segments cut or dropped by the clip planes or opaque geometry
  uint64_t rays_stopped = 0;      // mixed scenes: pixels with volume fragments whose ray meets opaque geometry
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
// Adds the per-tile parts of `tile` (counts, phase times, maxima) to `into`;
// ms_total and the set-up parts are left alone.
void add_stats(RenderStats& into, const RenderStats& tile);

}  // namespace zs
