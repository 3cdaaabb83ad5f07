// The sweep's event list: vertices ordered by view depth in a binary min-heap
// (B-Convert digest §1.1, stage 1). sweep_order() builds it once from every
// event vertex (`assign`, O(n)) and pops it in order; nothing is inserted
// while it runs (the near-plane clip adds faces, not events: near_clip.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace zs {

class VertexHeap {
 public:
  struct Entry {
    double z;
    uint32_t v;
  };

  void reserve(size_t n) { a_.reserve(n); }
  void push(double z, uint32_t v);
  // Builds the heap from unordered entries in O(n).
  void assign(const std::vector<Entry>& entries);
  Entry pop();
  Entry top() const { return entry(a_.front()); }
  bool empty() const { return a_.empty(); }
  size_t size() const { return a_.size(); }

 private:
  // An entry as one 128-bit key ordered as (z, v): the depth's bits mapped
  // so that unsigned order is numeric order (-0 as +0), then the vertex id,
  // which breaks ties so the sweep order is deterministic. One integer
  // comparison per step instead of two floating-point ones and a branch.
  using Key = unsigned __int128;
  static Key key(double z, uint32_t v) {
    if (z == 0) z = 0;  // -0 sorts with +0
    uint64_t u;
    std::memcpy(&u, &z, 8);
    u = (u >> 63) ? ~u : (u | (uint64_t(1) << 63));
    return (Key(u) << 32) | v;
  }
  static Entry entry(Key k) {
    uint64_t u = uint64_t(k >> 32);
    u = (u >> 63) ? (u & ~(uint64_t(1) << 63)) : ~u;
    double z;
    std::memcpy(&z, &u, 8);
    return {z, uint32_t(k)};
  }
  void sift_down(size_t i);
  std::vector<Key> a_;
};

}  // namespace zs
