// The per-view arrays of a ZSweep render (view-space vertices, face classes,
// sweep items, the order's face keys that become the tile bins), kept from
// one frame to the next of one mesh: a frame then writes memory that is
// already mapped instead of faulting in and zeroing fresh pages, which
// costs about as much as the rest of the set-up on a 64 M-tet mesh
// (docs/scaling.md). The arrays are the ones a single view holds at its
// peak anyway, so keeping them adds nothing to the peak.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/screen_triangle.h"
#include "render/volume/face_classes.h"
#include "render/volume/sweep_order.h"

namespace zs {

struct ViewBuffers {
  std::vector<ScreenVertex> sv;
  std::vector<FaceClass> cls;
  UninitVector<SweepItem> items;
  UninitVector<uint32_t> words;  // two per face (the order's keys), then the bins' entries
};

}  // namespace zs
