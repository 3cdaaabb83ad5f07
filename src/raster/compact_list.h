// B-Convert's compact list (B-Convert digest §4.3): the y range of a projected face and
// one [x_initial, x_final] candidate span per row, merged from the three edge
// lists l0 = v0v1, l1 = v1v2, l2 = v0v2 (vertices sorted by y).
#pragma once

#include <cstdint>
#include <vector>

#include "raster/bresenham_edges.h"

namespace zs {

struct CompactList {
  int32_t y0 = 0, y1 = 0;      // element 0: (y_initial, y_final)
  std::vector<int32_t> xi, xf;  // one span per row y0..y1
  int32_t rows() const { return y1 - y0 + 1; }
};

enum class EdgeWalker { Bresenham, RunLength };

// Scratch buffers reused across faces (no allocation per face once warm).
struct CompactScratch {
  std::vector<int32_t> l0, l1, l2;
};

// The seed's compaction: per row, the list with the smaller minimum supplies
// x_initial and the other list its maximum; ties go to l2 when v1 is right of
// l2 (case 2), to l0/l1 otherwise (case 3); single-row faces (case 1) get
// (min x, max x). Side of v1 by the sign of a cross product (B-Convert digest §4.4: the
// listing's unsigned slopes misclassify).
void build_compact_list(IPoint v0, IPoint v1, IPoint v2, EdgeWalker walker, CompactScratch& s, CompactList& out);

// The 3-D variant (B-Convert digest §5): each edge sampled in continuous screen
// coordinates with per-axis steps step_i = delta_i / (|delta_i in pixels| + 1)
// (Eq. 3.1), samples rounded to pixels and bucketed by row (min/max x).
void build_compact_list_dda(const double x[3], const double y[3], CompactList& out);

}  // namespace zs
