// What lies under the volume in each pixel of a mixed scene (docs/scene.md,
// "Volumes with geometry"): the opaque geometry drawn first on the same tiles
// — its shaded colour over the background and its view depth. The sweep cuts
// every ray's segments at that depth (as a clip plane cuts them) and
// composites the volume over that colour instead of the background.
#pragma once

#include <cstdint>

#include "raster/tile_capture.h"

namespace zs {

class OpaqueLayer {
 public:
  virtual ~OpaqueLayer() = default;
  // Tile `tile`'s pixels, row-major: stride() floats each, premultiplied
  // RGBA then view depth (+inf where no geometry is hit). Valid while the
  // tile is swept; called from any thread.
  virtual const float* tile(uint32_t tile) const = 0;
  virtual uint32_t stride() const = 0;
};

// The layer of tiles a geometry renderer drew into a TileCapture (RGBA, then
// Z as its fifth channel).
class CapturedOpaqueLayer : public OpaqueLayer {
 public:
  explicit CapturedOpaqueLayer(const TileCapture& c) : c_(c) {}
  const float* tile(uint32_t tile) const override { return c_.pixels(tile); }
  uint32_t stride() const override { return c_.grid().channels; }

 private:
  const TileCapture& c_;
};

}  // namespace zs
