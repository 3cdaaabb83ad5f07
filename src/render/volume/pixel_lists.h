// Per-pixel depth-sorted fragment lists (B-Convert digest §1.1, stage 2). The sweep
// composites a pixel's final fragments whenever a new one arrives there
// (tile_sweep.h), so a pixel rarely holds more than the few faces crossing
// the sweep plane at once (at most 3–4 on the benchmark meshes). The first
// kInline pending fragments therefore live in the pixel's own record, sorted;
// deeper ones overflow into a pooled, singly linked, sorted list per tile (no
// allocation per fragment; a free list hands out the most recently freed,
// cache-hot slot first), and move up as the front ones are composited.
//
// A record is one cache line: everything the sweep touches per fragment (the
// inline fragments, the overflow list ends, the inside count and the previous
// fragment). The compositing accumulators, which only SegmentBatch::flush and
// the compositor write, live apart in a PixelLight array (32 bytes, two
// pixels per line): a 64² tile's records and lights are 384 KiB, where
// records with their accumulators in a second line were 512 KiB, a whole
// 512 KiB L2, and the batch's apply loop (the second line's only reader)
// was a hot spot.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace zs {

// Order among fragments at the same depth: leave a cell before entering the
// next one, so a coincident exit/entry pair never opens a zero-length gap the
// wrong way round and the entry's scalar starts the next segment.
enum FragmentKind : uint32_t { kExit = 0, kInterior = 1, kEntry = 2 };

struct Fragment {  // 16 bytes: an overflow list entry
  float z;         // view depth minus the view's depth origin
  float s;         // scalar
  uint32_t next;   // pool index, kNil at the end
  uint32_t kind;   // FragmentKind
};

constexpr uint32_t kNil = UINT32_MAX;
constexpr int kInline = 4;

// No field is a character type: stores through those may alias anything and
// would make the compiler reload every member and pointer of the hot loops.
struct alignas(64) PixelRecord {
  // Line 1: pending fragments, shallowest first. z[0] is +inf when there are none,
  // so "has a fragment before z" is one compare.
  float z[kInline];
  float s[kInline];
  uint16_t kinds;         // FragmentKind of inline slot i in bits 2i, 2i+1
  uint16_t n;             // inline fragments; the overflow list is empty unless n == kInline
  uint16_t done;          // early-terminated: nothing behind matters
  uint16_t active;        // 1: listed in the tile's active pixels; 2: was, and is no longer; 0: never touched
  int16_t inside;         // entries minus exits (compositor.h), saturating
  uint16_t ovf;           // fragments in the overflow list, saturating at 65535
  float last_z, last_s;   // the previous fragment: where the next segment starts
  uint32_t head, tail;    // overflow list, kNil when empty
  uint32_t kind(int i) const { return (kinds >> (2 * i)) & 3u; }
  // Pending fragments in all (a saturated overflow count stays so until empty).
  uint32_t pending() const { return uint32_t(n) + ovf; }
  void reset() {
    z[0] = INFINITY;
    kinds = 0;
    n = done = active = 0;
    inside = 0;
    ovf = 0;
    last_z = last_s = 0;
    head = tail = kNil;
  }
};
static_assert(sizeof(PixelRecord) == 64, "one cache line per pixel");

// A pixel's premultiplied colour and transmittance so far, front to back.
struct PixelLight {
  double rgb[3];
  double T;
  void reset() {
    rgb[0] = rgb[1] = rgb[2] = 0;
    T = 1;
  }
};
static_assert(sizeof(PixelLight) == 32, "two pixels per cache line");

class PixelLists {
 public:
  // max_overflow bounds the overflow pool (the memory budget); it grows on demand.
  void reset(size_t max_overflow);

  // False when the fragment needs an overflow slot and the pool is at its
  // bound (the caller composites and retries). The caller counts successful
  // inserts into add_live() (once per face, off the per-fragment path).
  bool insert(PixelRecord& px, float z, float s, uint32_t kind) { return insert_counted(px, z, s, kind) != 0; }
  // insert() returning the pixel's pending count after it (0: not inserted),
  // which the sweep's list-length statistic needs without reloading the record.
  uint32_t insert_counted(PixelRecord& px, float z, float s, uint32_t kind) {
    const int n = px.n;
    // The sweep's common case: deeper than everything listed, and room inline.
    if (n < kInline && (n == 0 || px.z[n - 1] < z)) {
      px.z[n] = z;
      px.s[n] = s;
      px.kinds = uint16_t(px.kinds | (kind << (2 * n)));
      px.n = uint16_t(n + 1);
      return uint32_t(n + 1);
    }
    return insert_sorted(px, z, s, kind) ? px.pending() : 0;
  }
  void add_live(size_t inserted) {
    live_ += inserted;
    if (live_ > peak_) peak_ = live_;
  }

  // Removes the first k (<= n) inline fragments and moves overflow ones up.
  void drop_front(PixelRecord& px, int k) {
    const int n = px.n;
    for (int i = k; i < n; ++i) {
      px.z[i - k] = px.z[i];
      px.s[i - k] = px.s[i];
    }
    px.kinds = uint16_t(px.kinds >> (2 * k));
    px.n = uint16_t(n - k);
    live_ -= size_t(k);
    if (px.head != kNil) refill(px);
    if (px.n == 0) px.z[0] = INFINITY;
  }
  void clear(PixelRecord& px) {
    while (px.n > 0) drop_front(px, px.n);
  }

  // Pending fragments, inline and overflow, as of the last add_live (the
  // peak is sampled there: once per face).
  size_t live_fragments() const { return live_; }
  size_t peak_fragments() const { return peak_; }
  size_t overflow_fragments() const { return overflow_live_; }
  size_t peak_overflow_fragments() const { return overflow_peak_; }
  size_t max_overflow() const { return max_; }

 private:
  // a (za, ka) comes before a new fragment (z, kind): see FragmentKind.
  static bool before(float za, uint32_t ka, float z, uint32_t kind) { return za < z || (za == z && ka <= kind); }
  bool insert_sorted(PixelRecord& px, float z, float s, uint32_t kind);
  bool alloc(uint32_t* idx) {
    if (free_ != kNil) {
      *idx = free_;
      free_ = data_[free_].next;
    } else {
      if (used_ == cap_ && !grow()) return false;
      *idx = uint32_t(used_++);
    }
    if (++overflow_live_ > overflow_peak_) overflow_peak_ = overflow_live_;
    return true;
  }
  void release(uint32_t idx) {
    data_[idx].next = free_;
    free_ = idx;
    --overflow_live_;
  }
  bool overflow_insert(PixelRecord& px, float z, float s, uint32_t kind);
  bool overflow_push_front(PixelRecord& px, float z, float s, uint32_t kind);
  void refill(PixelRecord& px);
  bool grow();  // more slots, up to max_; false at the bound

  std::vector<Fragment> storage_;  // slots [0, used_) have been handed out
  Fragment* data_ = nullptr;
  size_t cap_ = 0, used_ = 0;
  uint32_t free_ = kNil;
  size_t max_ = 0, live_ = 0, peak_ = 0;
  size_t overflow_live_ = 0, overflow_peak_ = 0;
};

}  // namespace zs
