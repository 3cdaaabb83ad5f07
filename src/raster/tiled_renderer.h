// The one interface every renderer implements (the ZSweep volume engine, the
// sphere renderer, ...): a render prepared once for a view, then rendered
// tile by tile into a sink. Threads (tile_loop.h), the streaming image
// writers, `--memory-budget` and `--mpi` are written against this interface
// only, so each renderer gets them without knowing about them.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "raster/tile_grid.h"
#include "raster/tile_sink.h"

namespace zs {

class TiledRenderer {
 public:
  virtual ~TiledRenderer() = default;
  // The tiles this render is cut into (and the floats per pixel they carry).
  virtual const TileGrid& grid() const = 0;
  // The threads render_tiles uses.
  virtual int threads() const = 0;
  // Renders the given tiles (ids into grid(); every tile when null) into
  // `sink` and adds their counts to the renderer's running tile totals. A
  // tile's pixels never depend on which thread, rank or call rendered it.
  virtual void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) = 0;
  // The running tile totals (a renderer's own counters, trivially copyable)
  // as bytes, and adding another process's to them: MPI ranks send theirs to
  // rank 0, whose renderer (the same kind, so the layout agrees) sums them.
  virtual std::vector<uint8_t> tile_totals() const = 0;
  virtual void add_tile_totals(const std::vector<uint8_t>& other) = 0;
};

// Byte images of a renderer's trivially copyable totals.
template <class T>
std::vector<uint8_t> pod_bytes(const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<uint8_t> b(sizeof(T));
  std::memcpy(b.data(), &v, sizeof(T));
  return b;
}
template <class T>
bool pod_from_bytes(const std::vector<uint8_t>& b, T* out) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (b.size() != sizeof(T)) return false;
  std::memcpy(out, b.data(), sizeof(T));
  return true;
}

}  // namespace zs
