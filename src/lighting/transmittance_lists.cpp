#include "lighting/transmittance_lists.h"

#include <algorithm>
#include <cmath>

namespace zs {

void TransmittanceLists::reset(uint32_t size) {
  size_ = size;
  per_side_ = (size + kMapTile - 1) >> kMapTileShift;
  tiles_.assign(size_t(per_side_) * per_side_, Tile{});
  fragments_ = 0;
}

void TransmittanceLists::set_tile(uint32_t tx, uint32_t ty, std::vector<TranslucentTexel>& discs) {
  Tile& t = tiles_[size_t(ty) * per_side_ + tx];
  t = Tile{};
  if (discs.empty()) return;
  // By texel, then depth, then sphere: the products below then multiply in
  // one order whatever the tile's threads or its discs' arrival order.
  std::sort(discs.begin(), discs.end(), [](const TranslucentTexel& a, const TranslucentTexel& b) {
    if (a.texel != b.texel) return a.texel < b.texel;
    if (a.z != b.z) return a.z < b.z;
    return a.id < b.id;
  });
  constexpr uint32_t kTexels = kMapTile * kMapTile;
  t.start.assign(kTexels + 1, 0);
  for (const TranslucentTexel& d : discs) ++t.start[d.texel + 1];
  for (uint32_t i = 0; i < kTexels; ++i) t.start[i + 1] += t.start[i];
  t.z.resize(discs.size());
  t.trans.resize(discs.size());
  double tr = 1;
  uint32_t texel = kTexels;
  for (size_t k = 0; k < discs.size(); ++k) {
    const TranslucentTexel& d = discs[k];
    if (d.texel != texel) tr = 1, texel = d.texel;
    tr *= d.pass;
    // Depth rounded up, as the opaque depths are: a disc is never stored
    // nearer than it is.
    float z = float(d.z);
    if (double(z) < d.z) z = std::nextafter(z, INFINITY);
    t.z[k] = z;
    t.trans[k] = float(tr);
  }
}

void TransmittanceLists::count_fragments() {
  fragments_ = 0;
  for (const Tile& t : tiles_) fragments_ += t.z.size();
}

uint64_t TransmittanceLists::bytes() const {
  uint64_t b = tiles_.size() * sizeof(Tile);
  for (const Tile& t : tiles_) b += t.start.size() * 4 + t.z.size() * 8;
  return b;
}

}  // namespace zs
