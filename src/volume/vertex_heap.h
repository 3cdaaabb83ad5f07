// The sweep's event list: vertices ordered by view depth in a binary min-heap
// (digest §1.1, stage 1). A heap rather than a sort because the sweep may
// insert events while it runs (clipping vertices, future work).
#pragma once

#include <cstddef>
#include <cstdint>
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
  void assign(std::vector<Entry> entries);
  Entry pop();
  const Entry& top() const { return a_.front(); }
  bool empty() const { return a_.empty(); }
  size_t size() const { return a_.size(); }

 private:
  // Ties broken by vertex id so the sweep order is deterministic.
  static bool less(const Entry& x, const Entry& y) { return x.z < y.z || (x.z == y.z && x.v < y.v); }
  void sift_down(size_t i);
  std::vector<Entry> a_;
};

}  // namespace zs
