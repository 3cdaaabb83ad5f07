// What a sphere render counts and times (`render --stats`, docs/spheres.md).
#pragma once

#include <cstdint>

#include "render/spheres/sphere_visibility.h"

namespace zs {

struct SphereStats {
  double ms_total = 0, ms_setup = 0;   // setup: visibility and binning
  double ms_visibility = 0, ms_binning = 0, ms_grid = 0;
  double ms_ao_maps = 0;      // ambient occlusion: building its maps (batches: every frame)
  uint64_t ao_map_bytes = 0;  // the maps held at once (batches: the largest batch)
  uint64_t ao_batches = 0;    // 0: every map held across frames; else batches per frame
  uint64_t ao_translucent_fragments = 0;  // occluders "alpha": list entries over every map
  uint64_t spheres = 0, invalid = 0;
  VisibilityStats vis;
  uint64_t bin_entries = 0, tiles = 0, tile_size = 0;
  // Per tile, summed: spheres scanned, pixel centres tested, fragments whose
  // exact depth was computed, fragments rejected by the early depth test
  // (the sphere's nearest depth behind the buffer), depth writes.
  uint64_t spheres_scanned = 0, pixel_tests = 0, fragments = 0, early_rejected = 0, depth_writes = 0;
  uint64_t spheres_block_rejected = 0;  // skipped whole: behind every block of the tile under their box
  uint64_t rendered_pixels = 0;
  // Translucent modes (translucent_tile.h), per tile, summed (the peaks and
  // layers_max: the largest): fragments composited, pixels stopped by the
  // tolerance (Eq. 4.2), spheres skipped for alpha 0, passes over the
  // spheres (sorted's k-buffer passes too); peel and dual_peel: the most
  // layers at a pixel, and layers per pixel with a translucent fragment
  // (layer_sum / layer_pixels: the mean).
  uint64_t composited = 0, pixels_stopped = 0, spheres_clear = 0;
  uint64_t passes = 0, layers_max = 0, layer_sum = 0, layer_pixels = 0;
  uint64_t peak_rss_bytes = 0, memory_budget_bytes = 0, shared_bytes = 0;
};

// The per-tile parts of `tile` added to `into`.
inline void add_tile_stats(SphereStats& into, const SphereStats& tile) {
  into.spheres_scanned += tile.spheres_scanned;
  into.spheres_block_rejected += tile.spheres_block_rejected;
  into.pixel_tests += tile.pixel_tests;
  into.fragments += tile.fragments;
  into.early_rejected += tile.early_rejected;
  into.depth_writes += tile.depth_writes;
  into.rendered_pixels += tile.rendered_pixels;
  into.composited += tile.composited;
  into.pixels_stopped += tile.pixels_stopped;
  into.spheres_clear += tile.spheres_clear;
  into.passes += tile.passes;
  into.layers_max = into.layers_max > tile.layers_max ? into.layers_max : tile.layers_max;
  into.layer_sum += tile.layer_sum;
  into.layer_pixels += tile.layer_pixels;
}

}  // namespace zs
