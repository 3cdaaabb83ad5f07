// B-Convert's edge lists (B-Convert digest §4.2): for an edge a -> b with a.y <= b.y
// in integer pixels, exactly two entries per row from a.y to b.y: the first
// and last pixel the integer Bresenham chooses on that row, ascending.
// Interior run pixels are not stored.
#pragma once

#include <cstdint>
#include <vector>

namespace zs {

struct IPoint {
  int32_t x, y;
};

// The seed's modified Bresenham: steps every pixel of the driving axis.
// out is cleared and receives 2·(b.y - a.y + 1) x values.
void bresenham_edge_pairs(IPoint a, IPoint b, std::vector<int32_t>& out);

// Same output, computed a row at a time: the run of an x-major line on row r
// is closed-form (Bresenham's pixel on column k is row floor((2k·dy + dx) /
// 2dx)), so the cost is O(rows) instead of O(pixels) — the run-length line
// drawing the B-Convert digest's future work points to (§11).
void runlength_edge_pairs(IPoint a, IPoint b, std::vector<int32_t>& out);

}  // namespace zs
