// One tile's sweep (B-Convert digest §1.2) over its bin of faces, in the global sweep
// order: scan-convert each face inside the tile, insert its fragments into
// the pixel lists, and composite every fragment the sweep plane has passed —
// at z_target events for the whole tile, and for a single pixel whenever a
// new fragment arrives in it (its fragments before the plane are final then,
// and its record is in cache).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "raster/raster_target.h"
#include "raster/triangle_scan.h"
#include "base/view/camera.h"
#include "render/volume/face_classes.h"
#include "render/volume/near_clip.h"
#include "render/volume/opaque_layer.h"
#include "render/volume/pixel_lists.h"
#include "render/volume/render_settings.h"
#include "render/volume/segment_batch.h"
#include "base/optics/segment_integrator.h"
#include "render/volume/sweep_order.h"
#include "render/volume/tile_bins.h"

namespace zs {

struct RenderStats;

// Everything the tiles share, read-only while they run.
struct SweepShared {
  const Topology& topo;
  const RenderSettings& rs;
  const View& view;
  const SegmentIntegrator& integ;
  std::vector<ScreenVertex> sv;  // every vertex in view space
  std::vector<FaceClass> cls;    // per face
  std::vector<NearTriangle> near;
  SweepItems items;
  TileBins bins;
  double z_origin = 0;  // fragments store depth - z_origin
  const double* cell = nullptr;  // cell data: one value per tet (face_classes.h); null for point data
  const OpaqueLayer* under = nullptr;  // opaque geometry under the volume (mixed scenes), or null
};

// A bin entry staged for the sweep: its item with its screen triangle.
struct StagedItem {
  ScreenVertex tri[3];
  uint32_t vid[3];
  uint32_t id;
  float z_sweep;
  FaceClass cls;
};
constexpr size_t kStage = 1024;  // bin entries staged at once (~150 KB a thread)

// Per-thread scratch, reused from tile to tile.
// Aligned to its own cache lines: two threads' workspaces never share one.
struct alignas(128) TileWorkspace {
  // Pixel records, all in their reset state between tiles (only the ones a
  // tile touched are reset after it: on a sparse image most are never touched).
  std::vector<PixelRecord> px;
  std::vector<PixelLight> light;  // their accumulators, by the same index
  bool px_clean = false;          // false: reset every record and light before the next tile
  std::vector<uint32_t> active;   // pixels whose lists may be non-empty
  std::vector<uint32_t> touched;  // pixels that received a fragment this tile
  PixelLists lists;
  FaceSpans spans;
  FaceFragments frags;  // the benchmarks' timed path only
  std::unique_ptr<TriangleScanner> scanner;  // the render's scan strategy, with its scratch
  std::vector<float> out;  // the finished tile, RGBA
  std::vector<float> clip;  // per pixel, the depth interval the clip planes and opaque geometry keep
  std::vector<StagedItem> staged = std::vector<StagedItem>(kStage);
  std::unique_ptr<SegmentBatch> batch;  // exact integrator without early termination
};

// Sweeps tile `vp` (bin `tile`); leaves its premultiplied RGBA over the
// background in ws.out. Throws std::runtime_error when more than
// max_fragments must be pending at once.
void sweep_tile(const SweepShared& in, uint32_t tile, const Viewport& vp, uint64_t max_fragments, TileWorkspace& ws,
                RenderStats& stats);

}  // namespace zs
