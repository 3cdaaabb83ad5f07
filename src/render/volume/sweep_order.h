// The order in which the sweep projects faces (B-Convert digest §1.2), computed once
// per render: vertices are met by depth (ties by id; sweep_events.h) and each
// face is projected when the first of its vertices is swept. Every tile then
// sweeps its own faces in this global order, so each pixel receives the same
// fragments in the same order whatever the tiling.
//
// Faces that cannot produce a fragment — seen exactly edge-on, or covering no
// pixel centre of the image — are counted and left out here. An item is 8
// bytes (its face, the plane's depth when it is projected, and its tile when
// it touches only one, as most do); its vertices come from the topology and
// a box over several tiles is recomputed where needed, because at 100 M tets
// every byte per face is 200 MB (docs/scaling.md).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "base/util/uninit_vector.h"
#include "geometry/tets/topology.h"
#include "raster/screen_triangle.h"
#include "render/volume/face_classes.h"
#include "render/volume/near_clip.h"
#include "render/volume/sweep_events.h"

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

// One face (or near-plane piece) to project, 12 bytes.
struct SweepItem {
  uint32_t id;     // face id, or kNearItem | index into the near triangles
  float z_sweep;   // the sweep plane when the item is projected (-inf for near pieces)
  uint32_t tile;   // the one screen tile its pixel centres touch, or kManyTiles
};
constexpr uint32_t kManyTiles = UINT32_MAX;

struct SweepItems {
  // Near-plane triangles first (they start at z_near, before every vertex),
  // then faces in projection order.
  UninitVector<SweepItem> items;
  uint64_t degenerate = 0;  // faces left out: zero screen area (seen edge-on), no fragments
  uint64_t offscreen = 0;   // faces left out: no pixel centre of the image inside their box
  size_t size() const { return items.size(); }
  const SweepItem& operator[](size_t k) const { return items[k]; }
};

// `sv`: every vertex in view space; `done`: faces not to project (clipped
// faces, drawn as near pieces; empty: none); `events`: the vertices that
// start a face, in any order. Depths are stored relative to z_origin, as
// fragments are. Runs on the calling thread's TBB arena; the result does not
// depend on its thread count. `storage` and `words` (8 bytes a face of
// scratch) may hold a previous frame's arrays, reused (view_buffers.h).
SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       const std::vector<uint8_t>& done, const std::vector<SweepEvent>& events,
                       const std::vector<NearTriangle>& near, double z_origin, const ScreenTiling& tiling,
                       UninitVector<SweepItem> storage = {}, UninitVector<uint32_t>* words = nullptr);

// An item's screen triangle: a face's vertices in ascending id order.
inline void item_triangle(const SweepItems& items, size_t k, const Topology& topo, const std::vector<ScreenVertex>& sv,
                          const std::vector<NearTriangle>& near, ScreenVertex out[3]) {
  const uint32_t id = items[k].id;
  if (id & kNearItem) {
    const NearTriangle& nt = near[id & ~kNearItem];
    for (int c = 0; c < 3; ++c) out[c] = nt.v[c];
    return;
  }
  const auto fv = topo.face(id);
  for (int c = 0; c < 3; ++c) out[c] = sv[fv[c]];
}

// Its farthest vertex relative to z_origin: what z_target grows to.
inline float item_z_max(const ScreenVertex v[3], double z_origin) {
  return float(std::max({v[0].z, v[1].z, v[2].z}) - z_origin);
}

// Inclusive pixel-centre range [i0, i1] x [j0, j1] of a triangle inside a
// width x height image; false when it holds no pixel centre.
bool pixel_range(const ScreenVertex v[3], uint32_t width, uint32_t height, int* i0, int* i1, int* j0, int* j1);

// The tiles a kept item's pixel centres touch; the one tile's index
// (row-major), or kManyTiles.
TileBox item_tile_box(const ScreenVertex v[3], const ScreenTiling& tiling);
uint32_t single_tile(const TileBox& box, const ScreenTiling& tiling);

}  // namespace zs
