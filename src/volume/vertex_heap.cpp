#include "volume/vertex_heap.h"

#include <utility>

namespace zs {

void VertexHeap::push(double z, uint32_t v) {
  a_.push_back({z, v});
  size_t i = a_.size() - 1;
  while (i > 0) {
    const size_t p = (i - 1) / 2;
    if (!less(a_[i], a_[p])) break;
    std::swap(a_[i], a_[p]);
    i = p;
  }
}

void VertexHeap::sift_down(size_t i) {
  const size_t n = a_.size();
  for (;;) {
    const size_t l = 2 * i + 1, r = l + 1;
    size_t m = i;
    if (l < n && less(a_[l], a_[m])) m = l;
    if (r < n && less(a_[r], a_[m])) m = r;
    if (m == i) return;
    std::swap(a_[i], a_[m]);
    i = m;
  }
}

void VertexHeap::assign(std::vector<Entry> entries) {
  a_ = std::move(entries);
  for (size_t i = a_.size() / 2; i-- > 0;) sift_down(i);
}

VertexHeap::Entry VertexHeap::pop() {
  const Entry top = a_.front();
  a_.front() = a_.back();
  a_.pop_back();
  if (!a_.empty()) sift_down(0);
  return top;
}

}  // namespace zs
