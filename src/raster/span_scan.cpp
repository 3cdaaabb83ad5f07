#include "raster/span_scan.h"

#include <algorithm>
#include <cmath>

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace zs {

namespace {

// Faces whose candidate box is at most this many pixels are tested directly.
constexpr int64_t kDirectTestPixels = 12;

// The pixel range of row Y inside edge e, clamped to [x0, x1) (empty: lo > hi).
// sign·E is monotone along the row, so the inside set is a half-line: solve
// for its end, then step to the exact end with e's own inside test.
// `tests`/`fails` count the single-edge tests made.
struct EdgeTests {
  uint64_t tests = 0, fails = 0;
  bool operator()(const EdgeFn& e, int X, int Y) {
    const bool in = e.inside(X, Y);
    ++tests;
    fails += !in;
    return in;
  }
};

inline void edge_limit(const EdgeFn& e, double inv_slope, int Y, int x0, int x1, int* lo, int* hi, EdgeTests& in) {
  const double slope = -e.sign * e.dy;  // d(sign·E)/dX
  if (slope == 0) {
    if (!in(e, 0, Y)) *lo = x1, *hi = x0 - 1;  // constant along the row
    return;
  }
  // Where sign·E = 0: ax + (Y - ay)·dx/dy, clamped before the int conversion.
  const double root = std::clamp(e.ax + (double(Y) - e.ay) * inv_slope, double(x0) - 1, double(x1));
  if (slope > 0) {  // inside from some X on
    int c = int(std::ceil(root));
    if (c > x0 && in(e, c - 1, Y)) {
      do --c;
      while (c > x0 && in(e, c - 1, Y));
    } else {
      while (c < x1 && !in(e, c, Y)) ++c;
    }
    *lo = std::max(*lo, c);
  } else {  // inside up to some X
    int c = int(std::floor(root));
    if (c < x1 - 1 && in(e, c + 1, Y)) {
      do ++c;
      while (c < x1 - 1 && in(e, c + 1, Y));
    } else {
      while (c >= x0 && !in(e, c, Y)) --c;
    }
    *hi = std::min(*hi, c);
  }
}

#ifdef __AVX2__
// edge_limit for the three edges of a row at once (lane k: edge k; lane 3
// repeats edge 0 and is ignored), for the common case: each edge's rounded
// root is its exact end, which two tests per edge confirm (c inside, the
// pixel beyond it outside). The same arithmetic as EdgeFn::inside, lane by
// lane (no FMA), so the same ends; a row where any edge would step is
// handed back to edge_limit.
class RowEnds {
 public:
  RowEnds(const ScreenTriangle& t, const double inv_slope[3], int x0, int x1) {
    x0_d_ = _mm256_set1_pd(double(x0));
    x1_d_ = _mm256_set1_pd(double(x1));
    x1m1_ = _mm256_set1_pd(double(x1) - 1);
    neg_inf_ = _mm256_set1_pd(-INFINITY);
    pos_inf_ = _mm256_set1_pd(INFINITY);
    const EdgeFn& e0 = t.edge[0];
    const EdgeFn& e1 = t.edge[1];
    const EdgeFn& e2 = t.edge[2];
    ax_ = _mm256_setr_pd(e0.ax, e1.ax, e2.ax, e0.ax);
    ay_ = _mm256_setr_pd(e0.ay, e1.ay, e2.ay, e0.ay);
    dx_ = _mm256_setr_pd(e0.dx, e1.dx, e2.dx, e0.dx);
    dy_ = _mm256_setr_pd(e0.dy, e1.dy, e2.dy, e0.dy);
    sign_ = _mm256_setr_pd(e0.sign, e1.sign, e2.sign, e0.sign);
    inv_ = _mm256_setr_pd(inv_slope[0], inv_slope[1], inv_slope[2], inv_slope[0]);
    ties_ = _mm256_castsi256_pd(_mm256_setr_epi64x(-int64_t(e0.take_ties), -int64_t(e1.take_ties),
                                                   -int64_t(e2.take_ties), -int64_t(e0.take_ties)));
    lo_clamp_ = _mm256_set1_pd(double(x0) - 1);
    hi_clamp_ = _mm256_set1_pd(double(x1));
    for (int k = 0; k < 3; ++k) {
      const double slope = -t.edge[k].sign * t.edge[k].dy;
      pos_ |= unsigned(slope > 0) << k;
      flat_ |= unsigned(slope == 0) << k;
    }
    if (flat_) ok_ = false;  // rows constant along an edge: edge_limit's own case
    const __m256i pos = _mm256_setr_epi64x(-int64_t(pos_ & 1), -int64_t((pos_ >> 1) & 1),
                                           -int64_t((pos_ >> 2) & 1), -int64_t(pos_ & 1));
    pos_mask_ = _mm256_castsi256_pd(pos);
    // The pixel beyond the end: c - 1 where inside is X >= end, c + 1 where X <= end.
    step_ = _mm256_blendv_pd(_mm256_set1_pd(1.0), _mm256_set1_pd(-1.0), pos_mask_);
  }

  // The row's [lo, hi] as edge_limit gives it; false to leave the row to it.
  bool row(int Y, int* lo, int* hi, EdgeTests& in) const {
    if (!ok_) return false;
    const __m256d t = _mm256_sub_pd(_mm256_set1_pd(double(Y)), ay_);
    const __m256d root = _mm256_min_pd(_mm256_max_pd(_mm256_add_pd(ax_, _mm256_mul_pd(t, inv_)), lo_clamp_), hi_clamp_);
    const __m256d c = _mm256_blendv_pd(_mm256_round_pd(root, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                                       _mm256_round_pd(root, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC), pos_mask_);
    const __m256d row_term = _mm256_mul_pd(dx_, t);
    const __m256d a = inside(row_term, c), b = inside(row_term, _mm256_add_pd(c, step_));
    // edge_limit steps towards the beyond pixel where it is inside and c is
    // not at the box's end on that side (pos: c > x0; else c < x1 - 1), and
    // away from it where c is outside and not at the other end (pos: c < x1;
    // else c >= x0).
    const __m256d room_b = _mm256_blendv_pd(_mm256_cmp_pd(c, x1m1_, _CMP_LT_OQ), _mm256_cmp_pd(c, x0_d_, _CMP_GT_OQ), pos_mask_);
    const __m256d room_a = _mm256_blendv_pd(_mm256_cmp_pd(c, x0_d_, _CMP_GE_OQ), _mm256_cmp_pd(c, x1_d_, _CMP_LT_OQ), pos_mask_);
    const __m256d step = _mm256_or_pd(_mm256_and_pd(room_b, b), _mm256_andnot_pd(a, room_a));
    const unsigned ma = unsigned(_mm256_movemask_pd(a)) & 7u, mb = unsigned(_mm256_movemask_pd(b)) & 7u;
    in.tests += 6;
    in.fails += 6 - unsigned(__builtin_popcount(ma)) - unsigned(__builtin_popcount(mb));
    if (_mm256_movemask_pd(step) & 7) return false;
    // lo: the largest c of the lower ends, hi: the smallest of the upper ends
    // (lane 3, a copy of lane 0, changes neither).
    const __m256d lows = _mm256_blendv_pd(neg_inf_, c, pos_mask_), highs = _mm256_blendv_pd(c, pos_inf_, pos_mask_);
    const __m128d l2 = _mm_max_pd(_mm256_castpd256_pd128(lows), _mm256_extractf128_pd(lows, 1));
    const __m128d h2 = _mm_min_pd(_mm256_castpd256_pd128(highs), _mm256_extractf128_pd(highs, 1));
    const double l = _mm_cvtsd_f64(_mm_max_sd(l2, _mm_unpackhi_pd(l2, l2)));
    const double h = _mm_cvtsd_f64(_mm_min_sd(h2, _mm_unpackhi_pd(h2, h2)));
    if (l > double(*lo)) *lo = int(l);
    if (h < double(*hi)) *hi = int(h);
    return true;
  }

 private:
  // Lane k: EdgeFn::inside of edge k at column X (all ones or zero).
  __m256d inside(__m256d row_term, __m256d X) const {
    const __m256d E = _mm256_sub_pd(row_term, _mm256_mul_pd(dy_, _mm256_sub_pd(X, ax_)));
    const __m256d e = _mm256_mul_pd(sign_, E);
    const __m256d zero = _mm256_setzero_pd();
    const __m256d in = _mm256_or_pd(_mm256_cmp_pd(e, zero, _CMP_GT_OQ),
                                    _mm256_and_pd(_mm256_cmp_pd(e, zero, _CMP_EQ_OQ), ties_));
    return in;
  }

  __m256d ax_, ay_, dx_, dy_, sign_, inv_, ties_, lo_clamp_, hi_clamp_, pos_mask_, step_;
  __m256d x0_d_, x1_d_, x1m1_, neg_inf_, pos_inf_;
  unsigned pos_ = 0, flat_ = 0;
  bool ok_ = true;
};
#endif

}  // namespace

void scan_span(const ScreenTriangle& t, const Viewport& vp, FaceSpans& out, ScanCounters& c) {
  const int j0 = std::max(vp.y0, int(std::ceil(std::clamp(t.min_y, double(vp.y0) - 1, double(vp.y1) + 1))));
  const int j1 = std::min(vp.y1 - 1, int(std::floor(std::clamp(t.max_y, double(vp.y0) - 1, double(vp.y1) + 1))));
  if (j0 > j1) return;
  const int i0 = std::max(vp.x0, int(std::ceil(std::clamp(t.min_x, double(vp.x0) - 1, double(vp.x1) + 1))));
  const int i1 = std::min(vp.x1 - 1, int(std::floor(std::clamp(t.max_x, double(vp.x0) - 1, double(vp.x1) + 1))));
  if (i0 > i1) return;
  uint64_t hits = 0;
  // Tiny faces (most faces of a fine mesh at low resolution): solving for the
  // span ends costs more than testing the few candidates. Same predicate, so
  // the same pixels either way.
  if (int64_t(i1 - i0 + 1) * int64_t(j1 - j0 + 1) <= kDirectTestPixels) {
    for (int j = j0; j <= j1; ++j) {
      int first = i1 + 1, last = i0 - 1;
      for (int i = i0; i <= i1; ++i)
        if (t.inside(i, j)) first = std::min(first, i), last = i;
      if (first <= last) {
        out.push(j, first, last);
        hits += uint64_t(last - first + 1);
      }
    }
    const uint64_t tested = uint64_t(i1 - i0 + 1) * uint64_t(j1 - j0 + 1);
    c.pixel_tests += tested;
    c.pixel_hits += hits;
    c.pixel_misses += tested - hits;
    return;
  }
  double inv_slope[3];
  for (int k = 0; k < 3; ++k) inv_slope[k] = t.edge[k].dy != 0 ? t.edge[k].dx / t.edge[k].dy : 0.0;
  // Within the face's box: the exact ends never lie outside it.
  const int x0 = i0, x1 = i1 + 1;
  EdgeTests in;
#ifdef __AVX2__
  RowEnds ends(t, inv_slope, x0, x1);
#endif
  for (int j = j0; j <= j1; ++j) {
    int lo = x0, hi = x1 - 1;
#ifdef __AVX2__
    if (!ends.row(j, &lo, &hi, in))
#endif
      for (int k = 0; k < 3 && lo <= hi; ++k) edge_limit(t.edge[k], inv_slope[k], j, x0, x1, &lo, &hi, in);
    if (lo > hi) continue;
    out.push(j, lo, hi);
    hits += uint64_t(hi - lo + 1);
  }
  // The end searches test single edges: counted in pixel tests (three edges).
  c.pixel_tests += (in.tests + 2) / 3;
  c.pixel_misses += (in.fails + 2) / 3;
  c.pixel_hits += hits;
}

}  // namespace zs
