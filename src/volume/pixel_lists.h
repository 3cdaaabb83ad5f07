// Per-pixel depth-sorted fragment lists (digest §1.1 stage 2) in one pooled
// array per tile (no allocation per fragment): singly linked, with a tail
// index so that the sweep's common case — a fragment deeper than everything
// already listed — appends in O(1). Freed fragments go to a free list, which
// hands the most recently freed (cache-hot) slot out first.
//
// Everything the engine keeps for a pixel — list ends, inside count and the
// compositing accumulators — sits in one 64-byte record, so touching a pixel
// costs one cache line, and a tile's records (64² · 64 B = 256 KiB) stay in L2.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zs {

// Order among fragments at the same depth: leave a cell before entering the
// next one, so a coincident exit/entry pair never opens a zero-length gap the
// wrong way round and the entry's scalar starts the next segment.
enum FragmentKind : uint32_t { kExit = 0, kInterior = 1, kEntry = 2 };

struct Fragment {  // 16 bytes
  float z;         // view depth minus the view's depth origin
  float s;         // scalar
  uint32_t next;   // pool index, kNil at the end
  uint32_t kind;   // FragmentKind
};

constexpr uint32_t kNil = UINT32_MAX;

struct alignas(64) PixelRecord {
  double rgb[3];        // premultiplied colour so far, front to back
  double T;             // transmittance so far
  double last_L;        // the previous fragment's SegmentEnd (ln(1 - a))...
  float last_z, last_s; // ...its depth and scalar: where the next segment starts
  uint32_t head, tail;  // fragment list, kNil when empty
  int16_t inside;       // entries minus exits (compositor.h), saturating
  int16_t last_k;       // ...and its transfer-function interval
  uint16_t len;         // list length, saturating at 65535
  uint8_t done;         // early-terminated: nothing behind matters
  uint8_t active;       // listed in the tile's active pixels
  void reset() {
    rgb[0] = rgb[1] = rgb[2] = 0;
    T = 1;
    last_L = 0;
    last_z = last_s = 0;
    head = tail = kNil;
    inside = 0;
    last_k = 0;
    len = 0;
    done = active = 0;
  }
};
static_assert(sizeof(PixelRecord) == 64, "one cache line per pixel");

class FragmentPool {
 public:
  // max_fragments bounds the pool (the memory budget); it grows on demand.
  void reset(size_t max_fragments);

  // False when the pool is at its bound (the caller composites and retries).
  // Inline: once per fragment.
  bool insert(PixelRecord& px, float z, float s, uint32_t kind) {
    uint32_t idx = free_;
    if (idx != kNil) {
      free_ = data_[idx].next;
    } else {
      if (used_ == cap_ && !grow()) return false;
      idx = uint32_t(used_++);
    }
    Fragment& f = data_[idx];
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
    if (before(data_[px.tail], z, kind)) {  // the sweep's common case
      f.next = kNil;
      data_[px.tail].next = idx;
      px.tail = idx;
      return true;
    }
    if (!before(data_[px.head], z, kind)) {
      f.next = px.head;
      px.head = idx;
      return true;
    }
    uint32_t p = px.head;
    while (before(data_[data_[p].next], z, kind)) p = data_[p].next;
    f.next = data_[p].next;
    data_[p].next = idx;
    return true;
  }
  const Fragment& at(uint32_t idx) const { return data_[idx]; }
  // Returns a fragment already unlinked from its list to the free list.
  void release(uint32_t idx) {
    data_[idx].next = free_;
    free_ = idx;
    --live_;
  }
  // Removes and frees the first fragment of a non-empty list.
  void pop_front(PixelRecord& px) {
    const uint32_t idx = px.head;
    px.head = data_[idx].next;
    if (px.head == kNil) px.tail = kNil;
    release(idx);
    if (px.head == kNil) px.len = 0;
    else if (px.len != UINT16_MAX) --px.len;  // once saturated, stays so until empty
  }
  void clear(PixelRecord& px) {
    while (px.head != kNil) pop_front(px);
  }

  size_t live_fragments() const { return live_; }
  size_t peak_fragments() const { return peak_; }
  size_t max_fragments() const { return max_; }

 private:
  // Order among fragments at the same depth: see FragmentKind.
  static bool before(const Fragment& a, float z, uint32_t kind) { return a.z < z || (a.z == z && a.kind <= kind); }
  bool grow();  // more slots, up to max_; false at the bound

  std::vector<Fragment> storage_;  // slots [0, used_) have been handed out
  Fragment* data_ = nullptr;
  size_t cap_ = 0, used_ = 0;
  uint32_t free_ = kNil;
  size_t max_ = 0, live_ = 0, peak_ = 0;
};

}  // namespace zs
