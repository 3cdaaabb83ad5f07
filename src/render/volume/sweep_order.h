// The order in which the sweep projects faces (B-Convert digest §1.2), computed once
// per render: vertices leave the heap by depth (ties by id) and each face is
// projected when the first of its vertices is swept. Every tile then sweeps
// its own faces in this global order, so each pixel receives the same
// fragments in the same order whatever the tiling.
//
// Faces that cannot produce a fragment — seen exactly edge-on, or covering no
// pixel centre of the image — are counted and left out here, and each kept
// item carries the range of screen tiles its pixel centres touch (for the
// bins, tile_bins.h), so nothing downstream looks at them again.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/tets/topology.h"
#include "raster/screen_triangle.h"
#include "render/volume/face_classes.h"
#include "render/volume/near_clip.h"
#include "render/volume/vertex_heap.h"

namespace zs {

constexpr uint32_t kNearItem = 0x80000000u;  // item ids with this bit are near-plane triangles

// Inclusive range of screen tiles [c0, c1] x [r0, r1].
struct TileBox {
  uint32_t c0, c1, r0, r1;
};

// The image the items are binned for: width x height pixels, square tiles.
struct ScreenTiling {
  uint32_t width = 0, height = 0, tile = 64;
};

struct SweepItems {
  // Near-plane triangles first (they start at z_near, before every vertex),
  // then faces in projection order.
  std::vector<uint32_t> id;                  // face id, or kNearItem | index into the near triangles
  std::vector<std::array<uint32_t, 3>> tri;  // a face's vertex ids (unused for near items)
  std::vector<float> z_sweep;  // the sweep plane when the item is projected (-inf for near pieces)
  std::vector<float> z_max;    // its farthest vertex: what z_target grows to
  std::vector<TileBox> box;    // the tiles its pixel centres touch
  uint64_t degenerate = 0;     // faces left out: zero screen area (seen edge-on), no fragments
  uint64_t offscreen = 0;      // faces left out: no pixel centre of the image inside their box
  size_t size() const { return id.size(); }
};

// `sv`: every vertex in view space; `done`: faces not to project (clipped
// faces, drawn as near pieces); `events`: the vertices that start a face.
// Depths are stored relative to z_origin, as fragments are.
SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       const std::vector<uint8_t>& done, std::vector<VertexHeap::Entry> events,
                       const std::vector<NearTriangle>& near, double z_origin, const ScreenTiling& tiling);

// An item's screen triangle.
inline void item_triangle(const SweepItems& items, size_t k, const std::vector<ScreenVertex>& sv,
                          const std::vector<NearTriangle>& near, ScreenVertex out[3]) {
  const uint32_t id = items.id[k];
  if (id & kNearItem) {
    const NearTriangle& nt = near[id & ~kNearItem];
    for (int c = 0; c < 3; ++c) out[c] = nt.v[c];
    return;
  }
  for (int c = 0; c < 3; ++c) out[c] = sv[items.tri[k][c]];
}

// Inclusive pixel-centre range [i0, i1] x [j0, j1] of a triangle inside a
// width x height image; false when it holds no pixel centre.
bool pixel_range(const ScreenVertex v[3], uint32_t width, uint32_t height, int* i0, int* i1, int* j0, int* j1);

}  // namespace zs
