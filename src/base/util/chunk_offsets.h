// The prefix step of a stable parallel counting sort: chunks of the input
// (in input order) counted their entries per bucket into at[c * buckets + b];
// this turns the counts into where each chunk writes in each bucket, buckets
// in order and within a bucket the chunks in order, from `base`. Returns the
// buckets' starts (buckets + 1, the last is the end). Filling every chunk in
// input order then gives the same output for any number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zs {

inline std::vector<uint64_t> chunk_offsets(std::vector<uint64_t>& at, size_t chunks, size_t buckets,
                                           uint64_t base = 0) {
  std::vector<uint64_t> start(buckets + 1);
  uint64_t run = base;
  for (size_t b = 0; b < buckets; ++b) {
    start[b] = run;
    for (size_t c = 0; c < chunks; ++c) {
      const uint64_t n = at[c * buckets + b];
      at[c * buckets + b] = run;
      run += n;
    }
  }
  start[buckets] = run;
  return start;
}

}  // namespace zs
