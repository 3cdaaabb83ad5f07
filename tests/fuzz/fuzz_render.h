// Shared by the fuzz targets: renders a small image of whatever a reader
// accepted, so fuzzed geometry (NaN, huge or tiny coordinates, degenerate
// tets) and fuzzed settings reach the engine, not just the parser.
#pragma once

#include <algorithm>
#include <stdexcept>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "scene/scene.h"
#include "render/volume/zsweep_renderer.h"

namespace zs::fuzz {

// Meshes larger than this are parsed and validated but not rendered: a
// fuzz iteration must stay in milliseconds.
constexpr size_t kMaxRenderTets = 512;
constexpr uint32_t kMaxImage = 24;

// Errors the engine reports (std::runtime_error: a budget too small for the
// mesh, say) are expected outcomes.
inline void render_small(const TetMesh& mesh, RenderSettings rs, bool auto_camera, bool auto_tf) {
  rs.width = std::min(rs.width, kMaxImage);
  rs.height = std::min(rs.height, kMaxImage);
  rs.threads = 1;
  rs.progress = false;
  rs.tile_size = std::min<uint32_t>(std::max<uint32_t>(rs.tile_size, 8), 16);
  const Topology topo = build_topology(mesh);
  (void)validate(mesh, topo);
  (void)count_nonfinite_tets(mesh);
  if (mesh.num_tets() > kMaxRenderTets) return;
  struct Discard : TileSink {
    void tile(const TileRect&, const float*) override {}
  } sink;
  try {
    // The automatic camera refuses extents it cannot frame (runtime_error).
    if (auto_camera) rs.camera = zs::auto_camera(mesh, Projection::Orthographic, rs.width, rs.height);
    if (auto_tf) rs.tf = default_transfer_function(mesh);
    render_zsweep_tiles(mesh, topo, rs, sink, 0, nullptr);
  } catch (const std::runtime_error&) {
  }
}

}  // namespace zs::fuzz
