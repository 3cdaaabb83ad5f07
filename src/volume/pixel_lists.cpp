#include "volume/pixel_lists.h"

#include <algorithm>

namespace zs {

void FragmentPool::reset(size_t max_fragments) {
  max_ = std::min<size_t>(max_fragments, kNil - 1);
  used_ = 0;  // keeps the storage: the next tile reuses the memory
  free_ = kNil;
  live_ = peak_ = 0;
  cap_ = std::min(storage_.size(), max_);
  data_ = storage_.data();
}

bool FragmentPool::grow() {
  if (cap_ >= max_) return false;
  if (cap_ == storage_.size()) storage_.resize(std::min(max_, std::max<size_t>(1024, storage_.size() * 2)));
  cap_ = std::min(storage_.size(), max_);
  data_ = storage_.data();
  return true;
}

}  // namespace zs
