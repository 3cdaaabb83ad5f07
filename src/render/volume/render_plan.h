// How a ZSweep render fits its memory budget: shared state (vertices, faces,
// bins, the caller's sink), then per thread one tile's pixel state; the
// fragment pools get the rest.
#pragma once

#include <cstddef>
#include <cstdint>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "render/volume/render_settings.h"

namespace zs {

// Per-pixel bytes of a tile in flight (pixel record, with its first
// kInline fragments, its accumulators and its output), the bytes the plan charges per vertex,
// face and bin entry; overflow fragments are 16 bytes.
constexpr uint64_t kTilePixelBytes = 64 + 32 + 16;
uint64_t zsweep_shared_bytes(size_t num_points, size_t num_faces);

struct RenderPlan {
  uint64_t shared_bytes = 0, max_fragments = 0;  // max_fragments per thread's pool
};
// `tile_pixels`: the largest tile's pixels (TileGrid::max_tile_pixels).
RenderPlan plan_render(uint64_t budget, uint64_t shared_bytes, uint64_t tile_pixels, int threads);

// Throws the error a render would throw at set-up when the memory budget
// (settings.memory_budget_bytes, 0: default) cannot hold it, before anything
// large is allocated, for callers that open their sink (sink_bytes) only
// afterwards. Returns the shared bytes known so far.
uint64_t check_memory_budget(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings,
                             uint64_t sink_bytes);

}  // namespace zs
