// The exact screen footprint of a sphere (sphere impostors): per pixel, the
// ray through the pixel centre against the sphere in closed form, and the
// silhouette scanned as one run per row.
//
// Camera space: x right, y up, z forward (view depth). Screen mapping
// X = sx·a + ox, Y = oy − sy·b with (a, b) = (x, y) orthographic and
// (x/z, y/z) perspective; pixel (i, j)'s centre is (X, Y) = (i, j). The ray
// through a pixel is (a, b, 0) + t·(0, 0, 1) orthographic and t·(a, b, 1)
// perspective, so t is the view depth either way. Only depths > 0 count: a
// ray entering at depth <= 0 and leaving beyond 0 sees the exit surface.
//
// Numerics: perspective solves t²|d|² − 2t(c·d) + (|c|² − R²) = 0 with the
// discriminant written as |d|²R² − |c × d|² (no cancellation of m² against
// |d|²(|c|² − R²) far from the silhouette), the larger-magnitude root first
// and the other from the product of roots, and |c|² − R² as (|c| − R)(|c| + R).
#pragma once

#include <cmath>

#include "raster/raster_target.h"

namespace zs {

struct CameraPlane {  // the screen mapping above (sx, sy nonzero)
  bool perspective = false;
  double sx = 1, sy = 1, ox = 0, oy = 0;
};

struct SphereSetup {
  CameraPlane cam;
  double isx, isy;     // 1/sx, 1/sy
  double cx, cy, cz;   // centre, camera space
  double r, r2;        // radius, radius²
  double k;            // |c|² − R² ((|c| − R)(|c| + R)): < 0 when the eye is inside
  double rho2;         // orthographic: squared radius of the visible disk in (a, b)
};

// Sphere with centre (cx, cy, cz) in camera space and radius r > 0.
SphereSetup setup_sphere(const CameraPlane& cam, double cx, double cy, double cz, double r);

struct SphereHit {
  double t_in, t_out;  // entry and exit view depths along the pixel's ray, t_in <= t_out
  double t;            // the visible one: t_in if t_in > 0, else t_out
  bool inside;         // true when t is the exit (t_in <= 0): viewer inside, or the eye plane cuts it
};

// The ray through pixel centre (X, Y) against the sphere; false when it
// misses or meets it only at depth <= 0. A tangent ray (discriminant exactly
// 0) hits. Inline: it runs per pixel.
inline bool sphere_hit(const SphereSetup& s, double X, double Y, SphereHit* h) {
  const double a = (X - s.cam.ox) * s.isx, b = (s.cam.oy - Y) * s.isy;
  double t_in, t_out;
  if (!s.cam.perspective) {
    const double da = a - s.cx, db = b - s.cy;
    const double h2 = s.r2 - da * da - db * db;
    if (!(h2 >= 0)) return false;
    const double w = std::sqrt(h2);
    t_in = s.cz - w;
    t_out = s.cz + w;
  } else {
    const double q = a * a + b * b + 1;
    const double m = s.cx * a + s.cy * b + s.cz;  // c·d
    const double ux = s.cy - s.cz * b, uy = s.cz * a - s.cx, uz = s.cx * b - s.cy * a;  // c × d
    const double D = q * s.r2 - (ux * ux + uy * uy + uz * uz);
    if (!(D >= 0)) return false;
    const double w = std::sqrt(D);
    if (m >= 0) {
      const double den = m + w;  // > 0 unless m = D = 0 (then k = 0: both roots 0)
      t_out = den / q;
      t_in = den > 0 ? s.k / den : 0.0;
    } else {
      const double den = m - w;  // < 0
      t_in = den / q;
      t_out = s.k / den;
    }
  }
  if (!(t_out > 0)) return false;
  h->t_in = t_in;
  h->t_out = t_out;
  h->inside = !(t_in > 0);
  h->t = h->inside ? t_out : t_in;
  return true;
}

// Inclusive pixel-centre bounding range of the silhouette inside the
// viewport, conservative by a rounding margin (1e-6 pixel); false when no
// pixel centre of `vp` can be hit.
bool sphere_pixel_range(const SphereSetup& s, const Viewport& vp, int* i0, int* i1, int* j0, int* j1);

// A lower bound of the depth sphere_hit() gives at any pixel centre (X, Y)
// with X in [X0, X1] and Y in [Y0, Y1] where it hits, rounding included:
// the nearest point of the sphere inside that block's rays (orthographic:
// exact; perspective: the nearest point on the frustum's side planes that
// separate the block from the sphere's nearest point). -inf when the sphere
// is not wholly in front of the eye. Lets a renderer skip the exact hits of
// pixels already nearer than the sphere can be there.
double sphere_depth_bound(const SphereSetup& s, double X0, double X1, double Y0, double Y1);

// Appends one run per row (out.push(y, x0, x1)) holding exactly the pixel
// centres of `vp` for which sphere_hit() is true: each row's analytic
// interval, each end then stepped to with sphere_hit() itself. Counters:
// pixel_tests = sphere_hit evaluations, pixel_misses = those that failed,
// pixel_hits = pixels emitted.
void scan_sphere(const SphereSetup& s, const Viewport& vp, FaceSpans& out, ScanCounters& c);

}  // namespace zs
