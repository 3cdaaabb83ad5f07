#include "render/volume/vertex_heap.h"

#include <utility>

namespace zs {

void VertexHeap::push(double z, uint32_t v) {
  a_.push_back(key(z, v));
  size_t i = a_.size() - 1;
  while (i > 0) {
    const size_t p = (i - 1) / 2;
    if (!(a_[i] < a_[p])) break;
    std::swap(a_[i], a_[p]);
    i = p;
  }
}

void VertexHeap::sift_down(size_t i) {
  const size_t n = a_.size();
  for (;;) {
    const size_t l = 2 * i + 1, r = l + 1;
    size_t m = i;
    if (l < n && a_[l] < a_[m]) m = l;
    if (r < n && a_[r] < a_[m]) m = r;
    if (m == i) return;
    std::swap(a_[i], a_[m]);
    i = m;
  }
}

void VertexHeap::assign(const std::vector<Entry>& entries) {
  a_.resize(entries.size());
  for (size_t k = 0; k < entries.size(); ++k) a_[k] = key(entries[k].z, entries[k].v);
  for (size_t i = a_.size() / 2; i-- > 0;) sift_down(i);
}

// Floyd's bottom-up pop: the hole left by the root walks down to a leaf along
// the smaller children (one comparison per level instead of two), then the
// last entry is sifted up from there — usually a level or two, as it came
// from the bottom.
VertexHeap::Entry VertexHeap::pop() {
  const Key top = a_.front();
  const Key last = a_.back();
  a_.pop_back();
  const size_t n = a_.size();
  if (n == 0) return entry(top);
  // The smaller child is chosen without a branch: with keys in random order
  // that branch is a coin toss.
  size_t i = 0, l = 1;
  for (; l + 1 < n; l = 2 * i + 1) {
    const size_t c = l + size_t(a_[l + 1] < a_[l]);
    a_[i] = a_[c];
    i = c;
  }
  if (l < n) {  // a last child without a sibling
    a_[i] = a_[l];
    i = l;
  }
  while (i > 0) {
    const size_t p = (i - 1) / 2;
    if (!(last < a_[p])) break;
    a_[i] = a_[p];
    i = p;
  }
  a_[i] = last;
  return entry(top);
}

}  // namespace zs
