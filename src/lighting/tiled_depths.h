// A shadow map's depths kept by 64×64-texel tiles, stored only where a tile
// holds a caster (for an n-SM: also where it borders one, since its texels
// read their neighbours): every other texel reads +inf. A map fitted to the
// receivers in view is mostly empty once the ground is culled, so this saves
// the memory, and the time of clearing it, that a dense map would spend.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "raster/tile_sink.h"
#include "lighting/shadow_settings.h"

namespace zs {

constexpr uint32_t kMapTileShift = 6;
constexpr uint32_t kMapTile = 1u << kMapTileShift;  // texels per tile side
constexpr uint32_t kEmptyTile = 0xffffffffu;

class TiledDepths {
 public:
  // size × size texels of n depths each, every tile empty.
  void reset(uint32_t size, uint32_t n);
  // Gives tile (tx, ty) storage (+inf); returns its first texel. Not
  // thread-safe: allocate before filling in parallel.
  float* add_tile(uint32_t tx, uint32_t ty);
  void reserve_tiles(size_t count) { data_.reserve(count * kMapTile * kMapTile * n_); }

  uint32_t size() const { return size_; }
  uint32_t depths() const { return n_; }
  uint32_t tiles() const { return tiles_; }  // per side
  uint32_t stored_tiles() const { return uint32_t(data_.size() / (size_t(kMapTile) * kMapTile * n_)); }
  bool stored(uint32_t tx, uint32_t ty) const { return slot_[size_t(ty) * tiles_ + tx] != kEmptyTile; }
  float* tile(uint32_t tx, uint32_t ty) {
    return data_.data() + size_t(slot_[size_t(ty) * tiles_ + tx]) * kMapTile * kMapTile * n_;
  }
  // Texel (x, y)'s place in storage slot s, in texels.
  static size_t index(uint32_t s, uint32_t x, uint32_t y) {
    return (size_t(s) << (2 * kMapTileShift)) + ((y & (kMapTile - 1)) << kMapTileShift) + (x & (kMapTile - 1));
  }
  // Texel (x, y)'s n depths (x, y < size).
  const float* texel(uint32_t x, uint32_t y) const {
    const uint32_t s = slot_[size_t(y >> kMapTileShift) * tiles_ + (x >> kMapTileShift)];
    if (s == kEmptyTile) return empty_;
    return data_.data() + index(s, x, y) * n_;
  }
  // A 1-depth map's texels as plain pointers, for loops that read many: a
  // store into an output array cannot alias them (as it could the members),
  // so nothing is reloaded per texel.
  struct Reader {
    const uint32_t* slot;
    const float* data;
    uint32_t tiles;
    // Where texel (x, y) is: its tile (row-major) and its place in the
    // tile (index(0, x, y)); loops work these out vectorized first.
    uint32_t tile_of(uint32_t x, uint32_t y) const { return (y >> kMapTileShift) * tiles + (x >> kMapTileShift); }
    // The depth at that tile and place (+inf in an empty tile).
    float at(uint32_t tile, uint32_t off) const {
      const uint32_t s = slot[tile];
      return s == kEmptyTile ? INFINITY : data[(size_t(s) << (2 * kMapTileShift)) + off];
    }
  };
  Reader reader() const { return {slot_.data(), data_.data(), tiles_}; }  // n = 1 maps only
  // Row y's texels of tile column tx (kMapTile of them; n = 1 maps), or
  // nullptr where that tile is empty.
  const float* row(uint32_t tx, uint32_t y) const {
    const uint32_t s = slot_[size_t(y >> kMapTileShift) * tiles_ + tx];
    if (s == kEmptyTile) return nullptr;
    return data_.data() + index(s, 0, y) * n_;
  }
  uint64_t bytes() const { return data_.size() * sizeof(float) + slot_.size() * sizeof(uint32_t); }

 private:
  uint32_t size_ = 0, n_ = 1, tiles_ = 0;
  std::vector<uint32_t> slot_;  // tiles², kEmptyTile or storage slot
  std::vector<float> data_;     // slots × kMapTile² × n, texel-major
  float empty_[16] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY,
                      INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
};

// A rendered tile's depths as stored: floats rounded upwards, so a stored
// depth is never nearer than its caster. Returns the texels with a caster.
uint64_t round_depths_up(const double* z, size_t n, float* out);

// The tile loop's sink for a map being rendered: copies each finished tile
// (kMapTile-aligned, its storage added beforehand) into `out`.
struct TiledDepthsSink : TileSink {
  explicit TiledDepthsSink(TiledDepths& out) : c(&out) {}
  void tile(const TileRect& r, const float* px) override;
  TiledDepths* c;
};

// A dense size × size map (row-major, one depth per texel) kept by tiles: the
// tiles with a finite depth.
void tile_depths(const float* z, uint32_t size, TiledDepths* out);

// The n-SM pass (multi_depth.h) over a tiled 1-depth map: every stored tile
// and its eight neighbours, with the same values build_multi_depth gives.
void tiled_multi_depth(const TiledDepths& centre, uint32_t n, DepthSelect select, TiledDepths* out);

}  // namespace zs
