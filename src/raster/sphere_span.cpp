#include "raster/sphere_span.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace zs {

namespace {

constexpr double kInf = INFINITY;

// (x − y)(x + y): x² − y² without cancelling the squares.
inline double diff_sq(double x, double y) { return (x - y) * (x + y); }

// A closed interval of the line (possibly unbounded or empty) plus, when
// empty, the point where it came nearest to existing (a tangent row whose
// single pixel rounding may still hit).
struct Interval {
  double lo = kInf, hi = -kInf;
  bool has_seed = false;
  double seed = 0;
  bool empty() const { return !(lo <= hi); }
};

// {u : al·u² + 2·be·u + ga >= 0} ∩ {la·u + mu > 0}. The sets it is used for
// are convex (see scan_sphere), so the hull of the surviving pieces is the
// answer; it is only a first guess, the ends are then stepped to exactly.
Interval quad_set(double al, double be, double ga, double la, double mu) {
  double hlo = -kInf, hhi = kInf;  // the half-line
  if (la > 0) hlo = -mu / la;
  else if (la < 0) hhi = -mu / la;
  else if (!(mu > 0)) return {};
  Interval out;
  auto add = [&](double lo, double hi) {
    lo = std::max(lo, hlo), hi = std::min(hi, hhi);
    if (lo <= hi) out.lo = std::min(out.lo, lo), out.hi = std::max(out.hi, hi);
  };
  if (al == 0) {
    if (be > 0) add(-ga / (2 * be), kInf);
    else if (be < 0) add(-kInf, -ga / (2 * be));
    else if (ga >= 0) add(-kInf, kInf);
    return out;
  }
  const double disc = be * be - al * ga;
  if (!(disc >= 0)) {
    if (al > 0) add(-kInf, kInf);
    else {
      const double peak = -be / al;
      if (peak >= hlo && peak <= hhi) out.has_seed = true, out.seed = peak;
    }
    return out;
  }
  // Larger-magnitude root first, the other from the product of the roots.
  const double qq = -(be + std::copysign(std::sqrt(disc), be));
  double r1 = 0, r2 = 0;  // qq = 0 only when be = ga = 0: double root 0
  if (qq != 0) r1 = qq / al, r2 = ga / qq;
  if (r1 > r2) std::swap(r1, r2);
  if (al < 0) {
    add(r1, r2);
    if (out.empty()) {
      const double peak = -be / al;
      if (peak >= hlo && peak <= hhi) out.has_seed = true, out.seed = peak;
    }
  } else {
    add(-kInf, r1);
    add(r2, kInf);
  }
  return out;
}

// The a-interval of row b (camera-plane coordinates) whose rays hit at
// positive depth, as a guess. Orthographic: the visible disk. Perspective:
// D = (c·d)² − k|d|² >= 0, and with the eye outside (k > 0) also c·d > 0
// (both roots share the sign of c·d); eye inside (k < 0): the whole row.
// `al` is cx² − k (row_al), the same for every row.
Interval row_interval(const SphereSetup& s, double b, double al) {
  if (!s.cam.perspective) {
    const double db = b - s.cy;
    const double w2 = s.rho2 - db * db;
    if (!(w2 >= 0)) {
      Interval e;
      e.has_seed = s.rho2 > 0, e.seed = s.cx;
      return e;
    }
    const double w = std::sqrt(w2);
    return {s.cx - w, s.cx + w};
  }
  if (s.k < 0) return {-kInf, kInf};  // eye inside: every ray hits
  const double e = s.cy * b + s.cz;   // c·d = cx·a + e
  if (s.k == 0) return quad_set(0, 0, 1, s.cx, e);
  return quad_set(al, s.cx * e, e * e - s.k * (b * b + 1), s.cx, e);
}

// cx² − k = R² − (cy² + cz²), without cancelling the squares.
double row_al(const SphereSetup& s) { return diff_sq(s.r, std::hypot(s.cy, s.cz)); }

// The extent along one camera-plane axis (u: cu; the other: cv) of the
// perspective hit set with the eye outside: line v = const of the other axis
// is nonempty iff the plane through the eye containing it meets the sphere in
// front of the eye, i.e. (R² − cz²)v² + 2·cv·cz·v + (R² − cv²) >= 0 with
// cv·v + cz > 0; every line is nonempty when the sphere meets the u axis
// (R² > cv² + cz²).
Interval axis_extent(double r, double cv, double cz) {
  if (diff_sq(r, std::hypot(cv, cz)) >= 0) return {-kInf, kInf};
  return quad_set(diff_sq(r, std::fabs(cz)), cv * cz, diff_sq(r, std::fabs(cv)), cv, cz);
}

// Screen interval (X = scale·u + offset, or offset − scale·u when flip) of
// a camera-plane interval, to the inclusive pixel-centre range within
// [p0, p1), widened by a rounding margin. False when empty.
bool pixel_interval(double lo, double hi, double scale, double offset, bool flip, int p0, int p1, int* i0, int* i1) {
  if (!(lo <= hi)) return false;
  double X0 = flip ? offset - scale * hi : scale * lo + offset;
  double X1 = flip ? offset - scale * lo : scale * hi + offset;
  if (X0 > X1) std::swap(X0, X1);
  X0 -= 1e-6 + 1e-9 * std::fabs(X0);
  X1 += 1e-6 + 1e-9 * std::fabs(X1);
  const int a = std::max(p0, int(std::ceil(std::clamp(X0, double(p0) - 1, double(p1)))));
  const int b = std::min(p1 - 1, int(std::floor(std::clamp(X1, double(p0) - 1, double(p1)))));
  *i0 = a, *i1 = b;
  return a <= b;
}

}  // namespace

SphereSetup setup_sphere(const CameraPlane& cam, double cx, double cy, double cz, double r) {
  SphereSetup s;
  s.cam = cam;
  s.isx = 1.0 / cam.sx;
  s.isy = 1.0 / cam.sy;
  s.cx = cx, s.cy = cy, s.cz = cz;
  s.r = r;
  s.r2 = r * r;
  const double len = std::sqrt(cx * cx + cy * cy + cz * cz);
  s.k = diff_sq(len, r);
  // Orthographic: t_out = cz + h > 0 everywhere on the disk when cz > 0;
  // otherwise only where h > −cz, the disk of radius² R² − cz².
  s.rho2 = cz > 0 ? s.r2 : diff_sq(r, std::fabs(cz));
  return s;
}

bool sphere_pixel_range(const SphereSetup& s, const Viewport& vp, int* i0, int* i1, int* j0, int* j1) {
  Interval ua, ub;  // extents of a and b
  if (!s.cam.perspective) {
    if (!(s.rho2 > 0)) return false;
    const double rho = std::sqrt(s.rho2);
    ua = {s.cx - rho, s.cx + rho};
    ub = {s.cy - rho, s.cy + rho};
  } else if (s.k <= 0) {
    ua = ub = {-kInf, kInf};  // eye inside or on the sphere: conservative
  } else {
    ua = axis_extent(s.r, s.cx, s.cz);
    ub = axis_extent(s.r, s.cy, s.cz);
  }
  return pixel_interval(ua.lo, ua.hi, s.cam.sx, s.cam.ox, false, vp.x0, vp.x1, i0, i1) &&
         pixel_interval(ub.lo, ub.hi, s.cam.sy, s.cam.oy, true, vp.y0, vp.y1, j0, j1);
}

namespace {

// Perspective: the nearest depth of the sphere on the plane x = a0·z (for y,
// pass cy): the plane cuts it in a disk of radius ρ around c' = c − δ·n, and
// the plane's steepest in-plane direction (a0, 0, 1)/L rises by 1/L in z.
double plane_depth(double a0, double cx, double cz, double r) {
  const double L = std::sqrt(1 + a0 * a0);
  const double delta = (cx - a0 * cz) / L;
  const double rho = std::sqrt(std::max(0.0, diff_sq(r, std::fabs(delta))));
  return cz + delta * a0 / L - rho / L;
}

}  // namespace

double sphere_depth_bound(const SphereSetup& s, double X0, double X1, double Y0, double Y1) {
  if (!(s.cz - s.r > 0)) return -kInf;
  double a0 = (X0 - s.cam.ox) * s.isx, a1 = (X1 - s.cam.ox) * s.isx;
  double b0 = (s.cam.oy - Y1) * s.isy, b1 = (s.cam.oy - Y0) * s.isy;
  if (a0 > a1) std::swap(a0, a1);
  if (b0 > b1) std::swap(b0, b1);
  double z;
  if (!s.cam.perspective) {
    // The block's nearest ray to the centre: depth cz − √(r² − d²).
    const double da = std::max({a0 - s.cx, 0.0, s.cx - a1}), db = std::max({b0 - s.cy, 0.0, s.cy - b1});
    z = s.cz - std::sqrt(std::max(0.0, s.r2 - da * da - db * db));
  } else {
    // The sphere's nearest point c − r·ẑ seen at (a*, b*). Inside the block:
    // its depth. Otherwise the sphere's part inside the block's rays lies in
    // each half-space of a side plane that separates (a*, b*) from the
    // block, where (convexity) its nearest point is on that plane.
    const double zn = s.cz - s.r, as = s.cx / zn, bs = s.cy / zn;
    z = zn;
    if (as < a0) z = std::max(z, plane_depth(a0, s.cx, s.cz, s.r));
    if (as > a1) z = std::max(z, plane_depth(a1, s.cx, s.cz, s.r));
    if (bs < b0) z = std::max(z, plane_depth(b0, s.cy, s.cz, s.r));
    if (bs > b1) z = std::max(z, plane_depth(b1, s.cy, s.cz, s.r));
  }
  // Rounding: a near-tangent hit's depth carries about √ε of the sphere's
  // size (the square root of a cancelled discriminant).
  const double size = std::sqrt(s.cx * s.cx + s.cy * s.cy + s.cz * s.cz) + s.r;
  return z - 1e-7 * size;
}

// Why one run per row: the hit set in the camera plane is convex. Orthographic
// it is a disk. Perspective with the eye outside, it is {D >= 0, c·d > 0}, one
// nappe of the tangent cone cut by the plane z = 1 (an ellipse's inside, or
// the convex side of one hyperbola or parabola branch); eye inside, all of it.
void scan_sphere(const SphereSetup& s, const Viewport& vp, FaceSpans& out, ScanCounters& c) {
  int i0, i1, j0, j1;
  if (!sphere_pixel_range(s, vp, &i0, &i1, &j0, &j1)) return;
  const int x0 = vp.x0, xl = vp.x1 - 1;  // stepping may leave the guessed box, never the viewport
  uint64_t tests = 0, misses = 0, hits = 0;
  const double al = s.cam.perspective && s.k > 0 ? row_al(s) : 0.0;
  for (int j = j0; j <= j1; ++j) {
    const double Y = j;
    auto test = [&](int i) {
      SphereHit h;
      const bool in = sphere_hit(s, double(i), Y, &h);
      ++tests;
      misses += !in;
      return in;
    };
    const Interval row = row_interval(s, (s.cam.oy - Y) * s.isy, al);
    int lo = 1, hi = 0;
    bool have = !row.empty() && pixel_interval(row.lo, row.hi, s.cam.sx, s.cam.ox, false, x0, vp.x1, &lo, &hi);
    if (have) {
      // Left end: grow while the outside neighbour hits, else shrink to the first hit.
      if (test(lo)) {
        while (lo > x0 && test(lo - 1)) --lo;
      } else {
        do ++lo;
        while (lo <= hi && !test(lo));
        have = lo <= hi;
      }
      if (have) {  // right end; lo is a hit
        if (hi > lo && !test(hi)) {
          do --hi;
          while (hi > lo && !test(hi));
        } else {
          while (hi < xl && test(hi + 1)) ++hi;
        }
      }
    } else {
      // Empty guess: a grazing row may still hit at its nearest pixel.
      double seed;
      if (!row.empty()) seed = 0.5 * (std::max(row.lo, -1e300) + std::min(row.hi, 1e300));
      else if (row.has_seed) seed = row.seed;
      else continue;
      const double X = std::clamp(s.cam.sx * seed + s.cam.ox, double(x0), double(xl));
      lo = hi = int(std::lround(X));
      if (!test(lo)) continue;
      while (lo > x0 && test(lo - 1)) --lo;
      while (hi < xl && test(hi + 1)) ++hi;
      have = true;
    }
    if (!have) continue;
    out.push(j, lo, hi);
    hits += uint64_t(hi - lo + 1);
  }
  c.pixel_tests += tests;
  c.pixel_misses += misses;
  c.pixel_hits += hits;
}

}  // namespace zs
