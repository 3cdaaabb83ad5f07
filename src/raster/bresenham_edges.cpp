#include "raster/bresenham_edges.h"

#include <cstdlib>

namespace zs {

namespace {

// Appends x as the current row's last entry, keeping the pair ascending: when
// the row's first entry is larger (a leftward edge), x goes before it.
inline void push_as_row_max(std::vector<int32_t>& out, int32_t x) {
  if (out.size() % 2 == 1 && out.back() > x) {
    const int32_t first = out.back();
    out.back() = x;
    out.push_back(first);
  } else {
    out.push_back(x);
  }
}

}  // namespace

void bresenham_edge_pairs(IPoint a, IPoint b, std::vector<int32_t>& out) {
  out.clear();
  const int32_t dx = b.x - a.x, dy = b.y - a.y;  // dy >= 0
  const int32_t sx = dx < 0 ? -1 : 1;
  const int64_t ax = std::llabs(dx), ay = dy;
  int32_t x = a.x;
  bool row_open = true;
  if (ax >= ay) {
    // x-major: several pixels per row; store the first and the last.
    int64_t err = 2 * ay - ax;
    while (x != b.x) {
      if (row_open) {
        out.push_back(x);
        row_open = false;
      }
      if (err >= 0) {  // the next pixel is on the next row: close this one
        push_as_row_max(out, x);
        err -= 2 * ax;
        row_open = true;
      }
      err += 2 * ay;
      x += sx;
    }
  } else {
    // y-major: one pixel per row, stored twice.
    int64_t err = 2 * ax - ay;
    for (int32_t y = a.y; y != b.y; ++y) {
      out.push_back(x);
      out.push_back(x);
      if (err >= 0) {
        x += sx;
        err -= 2 * ay;
      }
      err += 2 * ax;
    }
  }
  if (out.empty()) out.push_back(x);
  else push_as_row_max(out, x);
  if (row_open) out.push_back(x);
}

void runlength_edge_pairs(IPoint a, IPoint b, std::vector<int32_t>& out) {
  const int64_t dx = b.x - a.x, dy = b.y - a.y;
  const int64_t ax = dx < 0 ? -dx : dx;
  if (ax < dy || dy == 0) {
    // y-major edges store one pixel per row anyway, and horizontal ones one
    // row: nothing to gain, use the stepping version.
    bresenham_edge_pairs(a, b, out);
    return;
  }
  out.resize(size_t(2 * (dy + 1)));
  // Column k (0..ax) lies on row floor((2k·dy + ax) / (2ax)); row r thus
  // starts at k_first(r) = ceil((2r - 1)·ax / (2dy)) (r >= 1, k_first(0) = 0).
  auto k_first = [&](int64_t r) -> int64_t {
    if (r <= 0) return 0;
    const int64_t num = (2 * r - 1) * ax, den = 2 * dy;
    return (num + den - 1) / den;
  };
  const int64_t sx = dx < 0 ? -1 : 1;
  int64_t k0 = 0;
  for (int64_t r = 0; r <= dy; ++r) {
    const int64_t k1 = r == dy ? ax : k_first(r + 1) - 1;
    const int32_t x0 = int32_t(a.x + sx * k0), x1 = int32_t(a.x + sx * k1);
    out[size_t(2 * r)] = x0 < x1 ? x0 : x1;
    out[size_t(2 * r + 1)] = x0 < x1 ? x1 : x0;
    k0 = k1 + 1;
  }
}

}  // namespace zs
