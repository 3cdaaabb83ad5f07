#include "render/surfaces/shade_batch.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>

#include <glm/geometric.hpp>

namespace zs {

namespace {

inline double dot3(double ax, double ay, double az, double bx, double by, double bz) {
  return (ax * bx + ay * by) + az * bz;
}

// Pixels [i0, i1) of the batch, all on the triangle whose set-up
// coefficients are q[0..17] (num, den, g, m: triangle_shade.h's order): the
// coefficients stay in registers and the loop runs across the pixels. The
// unnormalized normal goes to s*, the perspective ray direction to v*, as
// floats; normalize_vectors finishes them.
template <bool persp, bool points>
void hit_run(const View& view, const TriangleShade& ts, int i0, int i1, ShadeBatch& b) {
  const glm::dvec3 E = view.eye(), F = view.forward(), R = view.right(), U = view.up();
  const double isx = 1.0 / view.scale_x(), ox = view.offset_x();
  const double bY = b.cb;
  // A local copy (nothing the loop stores can alias it), as a struct so that
  // it is a few register moves, not a library call per run.
  struct Coeffs {
    double v[18];
  };
  static_assert(sizeof(TriangleShade) >= sizeof(Coeffs));
  Coeffs cs;
  std::memcpy(&cs, &ts.num[0], sizeof cs);
  const double* c = cs.v;
  const float cr = ts.color[0], cg = ts.color[1], cbl = ts.color[2];
  for (int i = i0; i < i1; ++i) {
    b.base[0][i] = cr, b.base[1][i] = cg, b.base[2][i] = cbl;
    const double a = (b.X[i] - ox) * isx;
    // The exact hit with the triangle's plane (triangle_shade.h); a ray
    // parallel to it (a sliver seen edge-on) takes the rasterized depth.
    const double num = c[0] + c[1] * a + c[2] * bY, den = c[3] + c[4] * a + c[5] * bY;
    const double sh = num / den;
    const bool good = (den != 0) & (std::abs(sh) < INFINITY);
    const double s = good ? sh : b.zbuf[i];
    b.ca[i] = a, b.depth[i] = s;
    if constexpr (persp && points) {
      const double wx = (F.x + a * R.x) + bY * U.x, wy = (F.y + a * R.y) + bY * U.y, wz = (F.z + a * R.z) + bY * U.z;
      b.px[i] = E.x + s * wx, b.py[i] = E.y + s * wy, b.pz[i] = E.z + s * wz;
    } else if constexpr (points) {
      b.px[i] = ((E.x + a * R.x) + bY * U.x) + s * F.x;
      b.py[i] = ((E.y + a * R.y) + bY * U.y) + s * F.y;
      b.pz[i] = ((E.z + a * R.z) + bY * U.z) + s * F.z;
    }
    // The shading normal's direction m0 + m1·a + m2·b (in doubles: the sum
    // cancels where den is small), normalized in floats below.
    b.sx[i] = float(c[9] + c[12] * a + c[15] * bY);
    b.sy[i] = float(c[10] + c[13] * a + c[16] * bY);
    b.sz[i] = float(c[11] + c[14] * a + c[17] * bY);
  }
}

// Normalizes the shading normals (the face normal g where the direction is
// zero or not finite) and turns the ray directions into unit vectors to the
// eye (orthographic: −F everywhere).
void normalize_vectors(const View& view, const TriangleShade* shades, ShadeBatch& b) {
  const int n = b.n;
  int bad = 0;
  for (int i = 0; i < n; ++i) {
    const float nx = b.sx[i], ny = b.sy[i], nz = b.sz[i];
    const float l2 = (nx * nx + ny * ny) + nz * nz;
    const bool ok = (l2 > 0) & (l2 < INFINITY);
    const float il = ok ? 1.f / std::sqrt(ok ? l2 : 1.f) : NAN;
    b.sx[i] = nx * il, b.sy[i] = ny * il, b.sz[i] = nz * il;
    bad += !ok;
    b.diffuse[i] = 0;
    b.specular[i] = 0;
  }
  if (bad)  // rare: a degenerate or overflowing interpolated normal (marked NaN above)
    for (int i = 0; i < n; ++i)
      if (b.sx[i] != b.sx[i]) {
        const double* g = shades[b.tri[i]].g;
        b.sx[i] = float(g[0]), b.sy[i] = float(g[1]), b.sz[i] = float(g[2]);
      }
  if (view.perspective()) {
    // The ray direction w = F + a·R + b·U (floats: only its direction is used).
    const glm::vec3 F(view.forward()), R(view.right()), U(view.up());
    const float bY = float(b.cb);
    const float fx = F.x + bY * U.x, fy = F.y + bY * U.y, fz = F.z + bY * U.z;
    for (int i = 0; i < n; ++i) {
      const float a = float(b.ca[i]);
      const float wx = fx + a * R.x, wy = fy + a * R.y, wz = fz + a * R.z;
      const float inv = -1.f / std::sqrt((wx * wx + wy * wy) + wz * wz);
      b.vx[i] = wx * inv, b.vy[i] = wy * inv, b.vz[i] = wz * inv;
    }
  } else {
    const glm::vec3 v = -glm::vec3(view.forward());
    for (int i = 0; i < n; ++i) b.vx[i] = v.x, b.vy[i] = v.y, b.vz[i] = v.z;
  }
}

}  // namespace

void surface_hits(const View& view, const TriangleShade* shades, ShadeBatch& b) {
  // By runs of pixels on one triangle (most pixels continue their
  // neighbour's triangle).
  static_assert(offsetof(TriangleShade, num) == 0 && offsetof(TriangleShade, m) == 9 * sizeof(double));
  const int n = b.n;
  const bool persp = view.perspective();
  b.cb = (view.offset_y() - b.Y) / view.scale_y();
  for (int i0 = 0; i0 < n;) {
    const uint32_t t = b.id[i0];
    int i1 = i0 + 1;
    while (i1 < n && b.id[i1] == t) ++i1;
    if (t == kNoShade) {
      i0 = i1;
      continue;
    }
    const TriangleShade& ts = shades[t];
    if (persp)
      b.points ? hit_run<true, true>(view, ts, i0, i1, b) : hit_run<true, false>(view, ts, i0, i1, b);
    else
      b.points ? hit_run<false, true>(view, ts, i0, i1, b) : hit_run<false, false>(view, ts, i0, i1, b);
    i0 = i1;
  }
  normalize_vectors(view, shades, b);
}

namespace {

template <bool spot>
void light_terms(const SurfaceShading& sh, const glm::dvec3& Ld, const glm::dvec3& P, const float* lit, ShadeBatch& b,
                 float* nh, float* w) {
  const float kd = float(sh.diffuse), ks = float(sh.specular), Lx = float(Ld.x), Ly = float(Ld.y), Lz = float(Ld.z);
  const double Px = P.x, Py = P.y, Pz = P.z;
  const int n = b.n;
  for (int i = 0; i < n; ++i) {
    float lx = Lx, ly = Ly, lz = Lz;
    if constexpr (spot) {  // to_light: normalize(position − p)
      const double qx = Px - b.px[i], qy = Py - b.py[i], qz = Pz - b.pz[i];
      const double inv = 1.0 / std::sqrt(dot3(qx, qy, qz, qx, qy, qz));
      lx = float(qx * inv), ly = float(qy * inv), lz = float(qz * inv);
    }
    const float nl = (b.sx[i] * lx + b.sy[i] * ly) + b.sz[i] * lz;
    const bool on = (lit[i] > 0) & (nl > 0);
    b.diffuse[i] += on ? lit[i] * kd * nl : 0.f;
    const float hx = lx + b.vx[i], hy = ly + b.vy[i], hz = lz + b.vz[i];
    const float ih = 1.f / std::sqrt((hx * hx + hy * hy) + hz * hz);
    const float c = ((b.sx[i] * hx + b.sy[i] * hy) + b.sz[i] * hz) * ih;
    nh[i] = c;
    w[i] = on & (c > 0) & (ks > 0) ? lit[i] * ks : 0.f;
  }
}

}  // namespace

void add_lights(const SurfaceShading& sh, const Light& light, const float* lit, ShadeBatch& b) {
  const int n = b.n;
  float nh[kShadeBatch], w[kShadeBatch];
  const glm::dvec3 Ld = to_light(light, glm::dvec3(0.0));
  if (light.type == LightType::Spot)
    light_terms<true>(sh, Ld, light.position, lit, b, nh, w);
  else
    light_terms<false>(sh, Ld, light.position, lit, b, nh, w);
  // nh^shininess (shininess_power: squaring for whole exponents), pixel-parallel.
  float pw[kShadeBatch];
  const double e = sh.shininess;
  if (e >= 0 && e <= 4096 && e == std::floor(e)) {
    // Highlights below 2^-40 are dropped: their powers would leave the
    // float range's normal numbers (slow on most CPUs) and add nothing seen.
    const float thr = e > 0 ? float(std::exp2(-40.0 / e)) : 0.f;
    float base[kShadeBatch];
    for (int i = 0; i < n; ++i) pw[i] = 1, base[i] = nh[i] >= thr ? nh[i] : 0.f;
    for (unsigned k = unsigned(e); k; k >>= 1) {
      if (k & 1)
        for (int i = 0; i < n; ++i) pw[i] *= base[i];
      for (int i = 0; i < n; ++i) base[i] *= base[i];
    }
  } else {
    const float ef = float(e);
    for (int i = 0; i < n; ++i) pw[i] = w[i] != 0 ? std::pow(nh[i], ef) : 0.f;
  }
  for (int i = 0; i < n; ++i) b.specular[i] += w[i] != 0 ? w[i] * pw[i] : 0.f;
}

void surface_colours(const ShadeBatch& b, double ambient, float rgb[3][kShadeBatch]) {
  const int n = b.n;
  const float am = float(ambient);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < n; ++i) {
      float c = b.base[k][i] * (am + b.diffuse[i]) + b.specular[i];
      c = c < 0.f ? 0.f : c;  // std::clamp's order: NaN stays
      c = 1.f < c ? 1.f : c;
      rgb[k][i] = c;
    }
}

void depth_range(const ShadeBatch& b, double* lo, double* hi) {
  // On integer keys that order doubles as numbers (negatives' magnitude bits
  // flipped), so that the loop vectorizes; a NaN depth gives a NaN bound.
  constexpr int64_t kMag = 0x7fffffffffffffff;
  int64_t kmin = INT64_MAX, kmax = INT64_MIN;
  const double* __restrict depth = b.depth;
  const uint32_t* __restrict id = b.id;
  for (int i = 0; i < b.n; ++i) {
    const int64_t bits = std::bit_cast<int64_t>(depth[i]);
    const int64_t key = bits ^ ((bits >> 63) & kMag);
    const int64_t m = -int64_t(id[i] != kNoShade);  // all ones where covered (bits, not a branch)
    const int64_t a = (key & m) | (INT64_MAX & ~m), c = (key & m) | (INT64_MIN & ~m);
    kmin = std::min(kmin, a);
    kmax = std::max(kmax, c);
  }
  if (kmin > kmax) {  // nothing covered
    *lo = INFINITY, *hi = -INFINITY;
    return;
  }
  *lo = std::bit_cast<double>(kmin ^ ((kmin >> 63) & kMag));
  *hi = std::bit_cast<double>(kmax ^ ((kmax >> 63) & kMag));
}

}  // namespace zs
