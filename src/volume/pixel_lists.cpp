#include "volume/pixel_lists.h"

#include <algorithm>

namespace zs {

PixelLists::PixelLists(size_t num_pixels, size_t max_fragments)
    : head_(num_pixels, kNil), tail_(num_pixels, kNil), len_(num_pixels, 0), in_active_(num_pixels, 0),
      max_fragments_(max_fragments < kNil ? max_fragments : kNil - 1) {
  pool_.reserve(std::min<size_t>(max_fragments_, 1 << 16));
}

static inline bool before(const Fragment& a, float z, uint32_t kind) {
  return a.z < z || (a.z == z && a.kind <= kind);
}

bool PixelLists::insert(uint32_t pixel, float z, float s, uint32_t kind) {
  uint32_t idx = free_;
  if (idx != kNil) {
    free_ = pool_[idx].next;
  } else {
    if (pool_.size() >= max_fragments_) return false;
    idx = uint32_t(pool_.size());
    pool_.push_back({});
  }
  Fragment& f = pool_[idx];
  f.z = z;
  f.s = s;
  f.kind = kind;
  ++live_;
  if (live_ > peak_) peak_ = live_;
  ++len_[pixel];
  uint32_t& h = head_[pixel];
  uint32_t& t = tail_[pixel];
  if (h == kNil) {
    f.next = kNil;
    h = t = idx;
    if (!in_active_[pixel]) {
      in_active_[pixel] = 1;
      active_.push_back(pixel);
    }
    return true;
  }
  if (before(pool_[t], z, kind)) {  // the sweep's common case
    f.next = kNil;
    pool_[t].next = idx;
    t = idx;
    return true;
  }
  if (!before(pool_[h], z, kind)) {
    f.next = h;
    h = idx;
    return true;
  }
  uint32_t p = h;
  while (before(pool_[pool_[p].next], z, kind)) p = pool_[p].next;
  f.next = pool_[p].next;
  pool_[p].next = idx;
  return true;
}

void PixelLists::pop_front(uint32_t pixel) {
  const uint32_t idx = head_[pixel];
  head_[pixel] = pool_[idx].next;
  if (head_[pixel] == kNil) tail_[pixel] = kNil;
  pool_[idx].next = free_;
  free_ = idx;
  --live_;
  --len_[pixel];
}

void PixelLists::clear(uint32_t pixel) {
  while (head_[pixel] != kNil) pop_front(pixel);
}

void PixelLists::compact_active() {
  size_t k = 0;
  for (uint32_t p : active_) {
    if (head_[p] != kNil)
      active_[k++] = p;
    else
      in_active_[p] = 0;
  }
  active_.resize(k);
}

}  // namespace zs
