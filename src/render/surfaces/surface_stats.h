// The surface renderer's counts and times (`render --stats`).
#pragma once

#include <cstdint>
#include <vector>

#include "lighting/shadow_map.h"
#include "lighting/triangle_projection.h"

namespace zs {

// Per-tile counts, summed over tiles (and MPI ranks): trivially copyable.
struct SurfaceTileTotals {
  uint64_t tiles = 0;
  uint64_t triangles_scanned = 0;  // (triangle, tile) pairs set up
  uint64_t fragments = 0;
  uint64_t depth_writes = 0;
  uint64_t rendered_pixels = 0;
  uint64_t shadow_tests = 0;       // (pixel, light) map lookups: k·n depth reads each
  uint64_t shadow_tests_empty = 0; // of those, decided by map tiles with no caster (no read)
  uint64_t shadow_rays = 0;        // (pixel, light) Embree rays (exact mode)
  uint64_t lit_pixels = 0;         // (pixel, light) pairs with lit > 0
  double ms_tiles = 0;             // summed over threads
  void operator+=(const SurfaceTileTotals& o) {
    tiles += o.tiles;
    triangles_scanned += o.triangles_scanned;
    fragments += o.fragments;
    depth_writes += o.depth_writes;
    rendered_pixels += o.rendered_pixels;
    shadow_tests += o.shadow_tests;
    shadow_tests_empty += o.shadow_tests_empty;
    shadow_rays += o.shadow_rays;
    lit_pixels += o.lit_pixels;
    ms_tiles += o.ms_tiles;
  }
};

struct SurfaceStats {
  double ms_total = 0, ms_setup = 0, ms_project = 0, ms_binning = 0, ms_shadows = 0, ms_fit = 0;
  ProjectCounts project;
  uint64_t bin_entries = 0;
  std::vector<ShadowMapStats> maps;  // one per light (map mode)
  double ms_rays_build = 0;          // exact mode: the BVH
  SurfaceTileTotals tiles;
  uint32_t tile_size = 0;
  uint64_t peak_rss_bytes = 0, memory_budget_bytes = 0;
};

}  // namespace zs
