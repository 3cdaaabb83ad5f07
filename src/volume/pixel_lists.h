// Per-pixel depth-sorted fragment lists in one pooled array (no allocation
// per fragment): singly linked, with a tail index so that the common case of
// the sweep — a fragment deeper than everything already listed — appends in
// O(1) ("tail-first insertion"). Freed fragments go to a free list.
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

class PixelLists {
 public:
  // max_fragments bounds the pool (the memory budget); it grows on demand.
  PixelLists(size_t num_pixels, size_t max_fragments);

  // False when the pool is at its bound (the caller composites and retries).
  bool insert(uint32_t pixel, float z, float s, uint32_t kind);

  uint32_t head(uint32_t pixel) const { return head_[pixel]; }
  const Fragment& at(uint32_t idx) const { return pool_[idx]; }
  uint32_t length(uint32_t pixel) const { return len_[pixel]; }
  // Removes and frees the first fragment of a non-empty list.
  void pop_front(uint32_t pixel);
  void clear(uint32_t pixel);

  // Pixels whose lists are non-empty (may hold a few stale entries; callers
  // skip empty ones and call compact_active()).
  const std::vector<uint32_t>& active() const { return active_; }
  void compact_active();

  size_t live_fragments() const { return live_; }
  size_t peak_fragments() const { return peak_; }
  size_t capacity_bytes() const { return pool_.capacity() * sizeof(Fragment); }

 private:
  std::vector<Fragment> pool_;
  std::vector<uint32_t> head_, tail_, len_;
  std::vector<uint8_t> in_active_;
  std::vector<uint32_t> active_;
  uint32_t free_ = kNil;
  size_t max_fragments_, live_ = 0, peak_ = 0;
};

}  // namespace zs
