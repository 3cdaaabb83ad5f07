// What a scan strategy writes: the pixels a face covers, as runs along rows
// (every strategy's inside set of a row is one run: screen_triangle.h), in
// plain reusable arrays (no allocation per fragment). The caller evaluates
// depth and scalar where it needs them (ScreenTriangle::attributes) and
// decides what a fragment means (a list entry, a depth sample, ...), so every
// renderer shares the same rasterization.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zs {

// The part of the image being rendered: columns [x0, x1), rows [y0, y1) of a
// full image `width` pixels wide (tiles render a sub-rectangle).
struct Viewport {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct ScanCounters {
  uint64_t pixel_tests = 0;   // inside tests performed
  uint64_t pixel_hits = 0;    // fragments produced ("intercepta")
  uint64_t pixel_misses = 0;  // tests that failed ("não intercepta")
  void operator+=(const ScanCounters& o) {
    pixel_tests += o.pixel_tests;
    pixel_hits += o.pixel_hits;
    pixel_misses += o.pixel_misses;
  }
};

// Pixels x0..x1 (inclusive) of row y.
struct RowSpan {
  int32_t y, x0, x1;
};

struct FaceSpans {
  std::vector<RowSpan> rows;
  size_t size() const { return rows.size(); }
  void clear() { rows.clear(); }
  void push(int32_t y, int32_t x0, int32_t x1) { rows.push_back({y, x0, x1}); }
  uint64_t pixels() const {
    uint64_t n = 0;
    for (const RowSpan& r : rows) n += uint64_t(r.x1 - r.x0 + 1);
    return n;
  }
};

// Per-pixel fragments (tests and simple consumers: expand_spans).
struct FaceFragments {
  std::vector<int32_t> x, y;
  std::vector<double> z, s;
  size_t size() const { return x.size(); }
  void clear() {
    x.clear();
    y.clear();
    z.clear();
    s.clear();
  }
  void push(int32_t px, int32_t py, double pz, double ps) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
    s.push_back(ps);
  }
};

}  // namespace zs
