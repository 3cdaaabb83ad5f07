#include "volume/pixel_lists.h"

#include <algorithm>

namespace zs {

void FragmentPool::reset(size_t max_fragments) {
  max_ = std::min<size_t>(max_fragments, kNil - 1);
  pool_.clear();  // keeps the capacity: the next tile reuses the memory
  free_ = kNil;
  live_ = peak_ = 0;
}

static inline bool before(const Fragment& a, float z, uint32_t kind) {
  return a.z < z || (a.z == z && a.kind <= kind);
}


bool FragmentPool::insert(PixelRecord& px, float z, float s, uint32_t kind) {
  uint32_t idx = free_;
  if (idx != kNil) {
    free_ = pool_[idx].next;
  } else {
    if (pool_.size() >= max_) return false;
    idx = uint32_t(pool_.size());
    pool_.push_back({});
  }
  Fragment& f = pool_[idx];
  f.z = z;
  f.s = s;
  f.kind = kind;
  if (++live_ > peak_) peak_ = live_;
  if (px.len != UINT16_MAX) ++px.len;
  if (px.head == kNil) {
    f.next = kNil;
    px.head = px.tail = idx;
    return true;
  }
  if (before(pool_[px.tail], z, kind)) {  // the sweep's common case
    f.next = kNil;
    pool_[px.tail].next = idx;
    px.tail = idx;
    return true;
  }
  if (!before(pool_[px.head], z, kind)) {
    f.next = px.head;
    px.head = idx;
    return true;
  }
  uint32_t p = px.head;
  while (before(pool_[pool_[p].next], z, kind)) p = pool_[p].next;
  f.next = pool_[p].next;
  pool_[p].next = idx;
  return true;
}

}  // namespace zs
