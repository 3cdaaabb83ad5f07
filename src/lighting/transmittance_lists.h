// Translucent occluders of an orthographic map, per texel (issue 24's
// `occluders: "alpha"`): the discs of spheres with 0 < α < 1 that lie nearer
// the light than the texel's nearest opaque disc, sorted by depth, each with
// the transmittance Π(1 − α) of itself and every disc before it. A point at
// light depth d behind the opaque depth gets nothing; in front of it, the
// transmittance of the discs nearer than d. Discs behind the opaque depth are
// dropped when built (a point past them is already blocked), so an
// all-opaque set stores no list at all.
//
// Kept by the map's 64×64-texel tiles (tiled_depths.h), only where a tile has
// a list: per stored tile, the start of each texel's run and the runs.
#pragma once

#include <cstdint>
#include <vector>

#include "lighting/tiled_depths.h"

namespace zs {

// A translucent disc at one texel of a tile being built.
struct TranslucentTexel {
  uint32_t texel;  // y·kMapTile + x within the tile
  uint32_t id;     // sphere index: ties in depth keep one order whatever the threads
  double z;        // light depth
  double pass;     // 1 − α
};

class TransmittanceLists {
 public:
  void reset(uint32_t size);  // size² texels, no list
  // Sets tile (tx, ty)'s lists from its discs (reordered here). Thread-safe
  // for distinct tiles once reset.
  void set_tile(uint32_t tx, uint32_t ty, std::vector<TranslucentTexel>& discs);
  // Transmittance from the light to a point at texel (x, y) with test limit
  // lim (its depth less the bias): the product over the discs nearer than
  // lim (z < lim: the opaque test's own rule), 1 with none.
  float transmittance(uint32_t x, uint32_t y, double lim) const {
    const Tile& t = tiles_[size_t(y >> kMapTileShift) * per_side_ + (x >> kMapTileShift)];
    if (t.start.empty()) return 1.f;
    const uint32_t i = ((y & (kMapTile - 1)) << kMapTileShift) | (x & (kMapTile - 1));
    const uint32_t first = t.start[i];
    uint32_t lo = first, hi = t.start[i + 1];
    while (lo < hi) {  // the first disc at or behind lim (runs are sorted by depth)
      const uint32_t mid = (lo + hi) >> 1;
      if (double(t.z[mid]) < lim) lo = mid + 1;
      else hi = mid;
    }
    return lo > first ? t.trans[lo - 1] : 1.f;
  }
  // Sums the stored discs; call once every tile is set.
  void count_fragments();
  uint64_t fragments() const { return fragments_; }
  uint64_t bytes() const;

 private:
  struct Tile {
    std::vector<uint32_t> start;  // kMapTile² + 1, or empty: no list in the tile
    std::vector<float> z, trans;  // depth (rounded up) and transmittance through it
  };
  uint32_t size_ = 0, per_side_ = 0;
  std::vector<Tile> tiles_;
  uint64_t fragments_ = 0;
};

}  // namespace zs
