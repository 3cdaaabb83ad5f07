#include "raster/screen_triangle.h"

#include "raster/raster_target.h"

#include <algorithm>
#include <cmath>

namespace zs {

namespace {

// Edge p -> q in the triangle's traversal order; `ccw` = the triangle's
// orientation. The sign comes from the orientation, not from evaluating the
// opposite vertex: on a sliver that vertex is within rounding of the edge's
// line and its sign can disagree with the other two edges, which would make
// the "inside" region an unbounded wedge instead of the triangle.
EdgeFn make_edge(const ScreenVertex& p, const ScreenVertex& q, bool ccw) {
  const bool forward = p.id < q.id;
  const ScreenVertex& a = forward ? p : q;
  const ScreenVertex& b = forward ? q : p;
  EdgeFn e;
  e.ax = a.x;
  e.ay = a.y;
  e.dx = b.x - a.x;
  e.dy = b.y - a.y;
  // E > 0 on the left of a -> b; the interior is on the left of p -> q when
  // the triangle turns counter-clockwise (det > 0).
  e.sign = (ccw == forward) ? 1.0 : -1.0;
  // Gradient of sign·E is sign·(-dy, dx): the direction of the interior.
  const double nx = -e.sign * e.dy, ny = e.sign * e.dx;
  e.take_ties = nx > 0 || (nx == 0 && ny > 0);
  return e;
}

}  // namespace

bool setup_triangle(const ScreenVertex v[3], bool perspective, ScreenTriangle* t) {
  const double e1x = v[1].x - v[0].x, e1y = v[1].y - v[0].y;
  const double e2x = v[2].x - v[0].x, e2y = v[2].y - v[0].y;
  const double det = screen_det(v);
  if (det == 0 || !std::isfinite(det)) return false;
  t->perspective = perspective;
  const bool ccw = det > 0;
  t->edge[0] = make_edge(v[1], v[2], ccw);
  t->edge[1] = make_edge(v[2], v[0], ccw);
  t->edge[2] = make_edge(v[0], v[1], ccw);
  t->x0 = v[0].x;
  t->y0 = v[0].y;
  auto plane = [&](double f0, double f1, double f2, double* c, double* gx, double* gy) {
    const double d1 = f1 - f0, d2 = f2 - f0;
    *c = f0;
    *gx = (d1 * e2y - d2 * e1y) / det;
    *gy = (d2 * e1x - d1 * e2x) / det;
  };
  double q[3], r[3];
  for (int k = 0; k < 3; ++k) {
    q[k] = perspective ? 1.0 / v[k].z : v[k].z;
    r[k] = perspective ? v[k].s / v[k].z : v[k].s;
  }
  plane(q[0], q[1], q[2], &t->q_c, &t->q_gx, &t->q_gy);
  plane(r[0], r[1], r[2], &t->r_c, &t->r_gx, &t->r_gy);
  t->z_lo = std::min({v[0].z, v[1].z, v[2].z});
  t->z_hi = std::max({v[0].z, v[1].z, v[2].z});
  t->s_lo = std::min({v[0].s, v[1].s, v[2].s});
  t->s_hi = std::max({v[0].s, v[1].s, v[2].s});
  t->min_x = std::min({v[0].x, v[1].x, v[2].x});
  t->max_x = std::max({v[0].x, v[1].x, v[2].x});
  t->min_y = std::min({v[0].y, v[1].y, v[2].y});
  t->max_y = std::max({v[0].y, v[1].y, v[2].y});
  return true;
}

void expand_spans(const ScreenTriangle& t, const FaceSpans& spans, FaceFragments& out) {
  for (const RowSpan& r : spans.rows)
    for (int32_t i = r.x0; i <= r.x1; ++i) {
      double z, s;
      t.attributes(i, r.y, &z, &s);
      out.push(i, r.y, z, s);
    }
}

}  // namespace zs
