// The order in which the sweep projects faces (digest §1.2), computed once
// per render: vertices leave the heap by depth (ties by id) and each face is
// projected when the first of its vertices is swept. Every tile then sweeps
// its own faces in this global order, so each pixel receives the same
// fragments in the same order whatever the tiling.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/topology.h"
#include "raster/screen_triangle.h"
#include "volume/face_classes.h"
#include "volume/near_clip.h"
#include "volume/vertex_heap.h"

namespace zs {

constexpr uint32_t kNearItem = 0x80000000u;  // item ids with this bit are near-plane triangles

struct SweepItems {
  // Near-plane triangles first (they start at z_near, before every vertex),
  // then faces in projection order.
  std::vector<uint32_t> id;    // face id, or kNearItem | index into the near triangles
  std::vector<float> z_sweep;  // the sweep plane when the item is projected (-inf for near pieces)
  std::vector<float> z_max;    // its farthest vertex: what z_target grows to
  size_t size() const { return id.size(); }
};

// `sv`: every vertex in view space; `done`: faces not to project (clipped
// faces, drawn as near pieces); `events`: the vertices that start a face.
// Depths are stored relative to z_origin, as fragments are.
SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       std::vector<uint8_t> done, std::vector<VertexHeap::Entry> events,
                       const std::vector<NearTriangle>& near, double z_origin);

}  // namespace zs
