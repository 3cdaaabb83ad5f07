// chunk_offsets: counts per (chunk, bucket) -> write positions, buckets in
// order and chunks in order within each, from a base.
#include <gtest/gtest.h>

#include "base/util/chunk_offsets.h"

namespace zs {
namespace {

TEST(ChunkOffsets, BucketMajorThenChunk) {
  // Two chunks, three buckets: chunk 0 has 2, 0, 1; chunk 1 has 1, 3, 0.
  std::vector<uint64_t> at = {2, 0, 1, 1, 3, 0};
  const std::vector<uint64_t> start = chunk_offsets(at, 2, 3, 10);
  EXPECT_EQ(start, (std::vector<uint64_t>{10, 13, 16, 17}));
  // Bucket 0: chunk 0 at 10, chunk 1 at 12; bucket 1: 13, 13; bucket 2: 16, 17.
  EXPECT_EQ(at, (std::vector<uint64_t>{10, 13, 16, 12, 13, 17}));
  std::vector<uint64_t> none;
  EXPECT_EQ(chunk_offsets(none, 0, 2), (std::vector<uint64_t>{0, 0, 0}));
}

}  // namespace
}  // namespace zs
