#include "render/volume/pixel_lists.h"

#include <algorithm>

namespace zs {

void PixelLists::reset(size_t max_overflow) {
  max_ = std::min<size_t>(max_overflow, kNil - 1);
  used_ = 0;  // keeps the storage: the next tile reuses the memory
  free_ = kNil;
  live_ = peak_ = 0;
  overflow_live_ = overflow_peak_ = 0;
  cap_ = std::min(storage_.size(), max_);
  data_ = storage_.data();
}

bool PixelLists::grow() {
  if (cap_ >= max_) return false;
  if (cap_ == storage_.size()) storage_.resize(std::min(max_, std::max<size_t>(1024, storage_.size() * 2)));
  cap_ = std::min(storage_.size(), max_);
  data_ = storage_.data();
  return true;
}

bool PixelLists::insert_sorted(PixelRecord& px, float z, float s, uint32_t kind) {
  int p = px.n;
  if (p == kInline) {
    // Full: the fragment, or the deepest inline one, goes to the overflow list.
    if (before(px.z[kInline - 1], px.kind(kInline - 1), z, kind)) return overflow_insert(px, z, s, kind);
    if (!overflow_push_front(px, px.z[kInline - 1], px.s[kInline - 1], px.kind(kInline - 1))) return false;
    p = kInline - 1;
  } else {
    ++px.n;
  }
  // Sorted insertion from the back.
  while (p > 0 && !before(px.z[p - 1], px.kind(p - 1), z, kind)) {
    px.z[p] = px.z[p - 1];
    px.s[p] = px.s[p - 1];
    --p;
  }
  px.z[p] = z;
  px.s[p] = s;
  // Kinds at and above p move up one slot (the one past the end drops out).
  const uint32_t low = (1u << (2 * p)) - 1;
  px.kinds = uint16_t(((px.kinds & low) | ((px.kinds & ~low) << 2) | (kind << (2 * p))) & 0xffu);
  return true;
}

bool PixelLists::overflow_insert(PixelRecord& px, float z, float s, uint32_t kind) {
  uint32_t idx;
  if (!alloc(&idx)) return false;
  if (px.ovf != UINT16_MAX) ++px.ovf;
  Fragment& f = data_[idx];
  f.z = z;
  f.s = s;
  f.kind = kind;
  if (px.head == kNil) {
    f.next = kNil;
    px.head = px.tail = idx;
  } else if (before(data_[px.tail].z, data_[px.tail].kind, z, kind)) {  // append
    f.next = kNil;
    data_[px.tail].next = idx;
    px.tail = idx;
  } else if (!before(data_[px.head].z, data_[px.head].kind, z, kind)) {
    f.next = px.head;
    px.head = idx;
  } else {
    uint32_t p = px.head;
    while (before(data_[data_[p].next].z, data_[data_[p].next].kind, z, kind)) p = data_[p].next;
    f.next = data_[p].next;
    data_[p].next = idx;
  }
  return true;
}

bool PixelLists::overflow_push_front(PixelRecord& px, float z, float s, uint32_t kind) {
  uint32_t idx;
  if (!alloc(&idx)) return false;
  if (px.ovf != UINT16_MAX) ++px.ovf;
  data_[idx] = {z, s, px.head, kind};
  if (px.head == kNil) px.tail = idx;
  px.head = idx;
  return true;
}

void PixelLists::refill(PixelRecord& px) {
  while (px.n < kInline && px.head != kNil) {
    const uint32_t idx = px.head;
    const Fragment& f = data_[idx];
    px.z[px.n] = f.z;
    px.s[px.n] = f.s;
    px.kinds = uint16_t(px.kinds | (f.kind << (2 * px.n)));
    ++px.n;
    px.head = f.next;
    release(idx);
    if (px.ovf != UINT16_MAX) --px.ovf;  // once saturated, stays so until empty
  }
  if (px.head == kNil) px.tail = kNil, px.ovf = 0;
}

}  // namespace zs
