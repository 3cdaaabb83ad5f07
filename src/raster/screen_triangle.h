// A face in screen space, set up once per projection: its three edge
// functions (for the inside test) and the plane equations of depth and scalar.
//
// Inside test (shared by every scan strategy so they agree bit for bit):
// edge k runs between vertices with ids a < b, always evaluated in that
// canonical order, E(X, Y) = (bx - ax)(Y - ay) - (by - ay)(X - ax). The same
// edge of two neighbouring faces therefore yields the same number, and the tie
// rule (a pixel centre exactly on an edge belongs to the face whose interior
// lies towards +X, or +Y when the edge is horizontal) gives a centre on a
// shared edge to exactly one of two faces lying on opposite sides of it. A
// ray through a shared edge thus meets one fragment, never two or none.
//
// Interpolation: orthographic depth and scalar are linear in (X, Y);
// perspective 1/z and s/z are (perspective-correct interpolation).
#pragma once

#include <algorithm>
#include <cstdint>

namespace zs {

struct ScreenVertex {
  double x, y;   // continuous pixel coordinates (pixel centre (i, j) at (i, j))
  double z;      // view depth (> 0; perspective interpolates 1/z)
  double s;      // scalar
  uint32_t id;   // mesh vertex id, orders the edges canonically
};

struct EdgeFn {
  double ax, ay, dx, dy;  // canonical start and direction
  double sign;            // +1 or -1: sign of E inside this face
  bool take_ties;         // tie rule result for this face
  // E at (X, Y) in canonical order; identical for both faces of an edge.
  double eval(double X, double Y) const { return dx * (Y - ay) - dy * (X - ax); }
  bool inside(double X, double Y) const {
    const double e = sign * eval(X, Y);
    return e > 0 || (e == 0 && take_ties);
  }
};

struct ScreenTriangle {
  EdgeFn edge[3];
  // Attribute planes: value(X, Y) = c + gx·(X - x0) + gy·(Y - y0).
  double x0, y0;
  double q_c, q_gx, q_gy;  // z (ortho) or 1/z (perspective)
  double r_c, r_gx, r_gy;  // s (ortho) or s/z (perspective)
  double z_lo, z_hi, s_lo, s_hi;  // clamp ranges: keeps slivers seen edge-on sane
  double min_x, max_x, min_y, max_y;
  bool perspective;

  bool inside(double X, double Y) const {
    return edge[0].inside(X, Y) && edge[1].inside(X, Y) && edge[2].inside(X, Y);
  }
  // Depth and scalar at a pixel centre known to be inside. Inline: every
  // fragment of every renderer comes through here.
  void attributes(double X, double Y, double* z, double* s) const {
    const double dx = X - x0, dy = Y - y0;
    const double q = q_c + q_gx * dx + q_gy * dy;
    const double r = r_c + r_gx * dx + r_gy * dy;
    const double zz = perspective ? 1.0 / q : q;
    const double ss = perspective ? r * zz : r;
    *z = std::clamp(zz, z_lo, z_hi);
    *s = std::clamp(ss, s_lo, s_hi);
  }
};

// Twice the signed screen area (the edge-function determinant); zero or
// non-finite for a triangle that covers no pixel centre's interior.
inline double screen_det(const ScreenVertex v[3]) {
  return (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
}

// Returns false (and sets nothing useful) for a triangle with zero screen area:
// seen exactly edge-on, it contains no pixel centre in its interior.
bool setup_triangle(const ScreenVertex v[3], bool perspective, ScreenTriangle* t);

struct FaceSpans;
struct FaceFragments;
// Appends the fragments (pixel, depth, scalar) of a face's spans.
void expand_spans(const ScreenTriangle& t, const FaceSpans& spans, FaceFragments& out);

}  // namespace zs
