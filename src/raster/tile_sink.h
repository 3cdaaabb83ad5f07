// Where finished tiles go: an image in memory, a streaming file writer, an
// MPI message. Calls are serialized; tiles arrive in any order.
#pragma once

#include "raster/tile_grid.h"

namespace zs {

class TileSink {
 public:
  virtual ~TileSink() = default;
  // r.width()·r.height() pixels, row-major, `channels` floats each (the
  // grid's: premultiplied RGBA, then Z when the renderer has one).
  virtual void tile(const TileRect& r, const float* pixels) = 0;
};

// Keeps nothing: frames that are only timed, and tiles written in place.
struct NullSink : TileSink {
  void tile(const TileRect&, const float*) override {}
};

}  // namespace zs
