#include "surface/shade_batch.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/geometric.hpp>

namespace zs {

namespace {

inline double dot3(double ax, double ay, double az, double bx, double by, double bz) {
  return (ax * bx + ay * by) + az * bz;
}

// Pixels [i0, i1) of the batch, all on the triangle whose set-up
// coefficients are q[0..17] (num, den, g, m: triangle_shade.h's order): the
// coefficients stay in registers and the loop runs across the pixels.
template <bool persp>
void hit_run(const View& view, double bY, const double* __restrict q, int i0, int i1, ShadeBatch& b) {
  const glm::dvec3 E = view.eye(), F = view.forward(), R = view.right(), U = view.up();
  const double isx = 1.0 / view.scale_x(), ox = view.offset_x();
  double c[18];  // a local copy: nothing the loop stores can alias it
  std::copy(q, q + 18, c);
  for (int i = i0; i < i1; ++i) {
    const double a = (b.X[i] - ox) * isx;
    // The exact hit with the triangle's plane (triangle_shade.h); a ray
    // parallel to it (a sliver seen edge-on) takes the rasterized depth.
    const double num = c[0] + c[1] * a + c[2] * bY, den = c[3] + c[4] * a + c[5] * bY;
    const double sh = num / den;
    const bool good = (den != 0) & (std::abs(sh) < INFINITY);
    const double s = good ? sh : b.zbuf[i];
    double px, py, pz;
    if constexpr (persp) {
      const double wx = (F.x + a * R.x) + bY * U.x, wy = (F.y + a * R.y) + bY * U.y, wz = (F.z + a * R.z) + bY * U.z;
      px = E.x + s * wx, py = E.y + s * wy, pz = E.z + s * wz;
      const double inv = 1.0 / std::sqrt(dot3(wx, wy, wz, wx, wy, wz));
      b.vx[i] = -wx * inv, b.vy[i] = -wy * inv, b.vz[i] = -wz * inv;
    } else {
      px = ((E.x + a * R.x) + bY * U.x) + s * F.x;
      py = ((E.y + a * R.y) + bY * U.y) + s * F.y;
      pz = ((E.z + a * R.z) + bY * U.z) + s * F.z;
      b.vx[i] = -F.x, b.vy[i] = -F.y, b.vz[i] = -F.z;
    }
    b.px[i] = px, b.py[i] = py, b.pz[i] = pz;
    b.depth[i] = s;
    const double gx = c[6], gy = c[7], gz = c[8];
    b.gx[i] = gx, b.gy[i] = gy, b.gz[i] = gz;
    // The shading normal: normalize(m0 + m1·a + m2·b); the face normal
    // where that is zero or not finite.
    const double nx = c[9] + c[12] * a + c[15] * bY;
    const double ny = c[10] + c[13] * a + c[16] * bY;
    const double nz = c[11] + c[14] * a + c[17] * bY;
    const double l2 = dot3(nx, ny, nz, nx, ny, nz);
    const bool ok = (l2 > 0) & (l2 < INFINITY);
    const double il = 1.0 / std::sqrt(ok ? l2 : 1.0);
    b.sx[i] = ok ? nx * il : gx, b.sy[i] = ok ? ny * il : gy, b.sz[i] = ok ? nz * il : gz;
    b.diffuse[i] = 0;
    b.specular[i] = 0;
  }
}

}  // namespace

void surface_hits(const View& view, double Y, const TriangleShade* shades, ShadeBatch& b) {
  // By runs of pixels on one triangle (most pixels of a row continue their
  // neighbour's triangle).
  static_assert(offsetof(TriangleShade, num) == 0 && offsetof(TriangleShade, m) == 9 * sizeof(double));
  const double bY = (view.offset_y() - Y) / view.scale_y();
  const int n = b.n;
  for (int i0 = 0; i0 < n;) {
    const uint32_t t = b.tri[i0];
    int i1 = i0 + 1;
    while (i1 < n && b.tri[i1] == t) ++i1;
    const TriangleShade& ts = shades[t];
    if (view.perspective())
      hit_run<true>(view, bY, &ts.num[0], i0, i1, b);
    else
      hit_run<false>(view, bY, &ts.num[0], i0, i1, b);
    for (int k = 0; k < 3; ++k)
      for (int i = i0; i < i1; ++i) b.base[k][i] = ts.color[k];
    i0 = i1;
  }
}

namespace {

template <bool spot>
void light_terms(const SurfaceShading& sh, const glm::dvec3& Ld, const glm::dvec3& P, const double* lit, ShadeBatch& b,
                 double* nh, double* w) {
  const double kd = sh.diffuse, ks = sh.specular, Lx = Ld.x, Ly = Ld.y, Lz = Ld.z, Px = P.x, Py = P.y, Pz = P.z;
  const int n = b.n;
  for (int i = 0; i < n; ++i) {
    double lx = Lx, ly = Ly, lz = Lz;
    if constexpr (spot) {  // to_light: normalize(position − p)
      const double qx = Px - b.px[i], qy = Py - b.py[i], qz = Pz - b.pz[i];
      const double inv = 1.0 / std::sqrt(dot3(qx, qy, qz, qx, qy, qz));
      lx = qx * inv, ly = qy * inv, lz = qz * inv;
    }
    const double nl = dot3(b.sx[i], b.sy[i], b.sz[i], lx, ly, lz);
    const bool on = (lit[i] > 0) & (nl > 0);
    b.diffuse[i] += on ? lit[i] * kd * nl : 0.0;
    const double hx = lx + b.vx[i], hy = ly + b.vy[i], hz = lz + b.vz[i];
    const double ih = 1.0 / std::sqrt(dot3(hx, hy, hz, hx, hy, hz));
    const double c = dot3(b.sx[i], b.sy[i], b.sz[i], hx * ih, hy * ih, hz * ih);
    nh[i] = c;
    w[i] = on & (c > 0) & (ks > 0) ? lit[i] * ks : 0.0;
  }
}

}  // namespace

void add_lights(const SurfaceShading& sh, const Light& light, const double* lit, ShadeBatch& b) {
  const int n = b.n;
  double nh[kShadeBatch], w[kShadeBatch];
  const glm::dvec3 Ld = to_light(light, glm::dvec3(0.0));
  if (light.type == LightType::Spot)
    light_terms<true>(sh, Ld, light.position, lit, b, nh, w);
  else
    light_terms<false>(sh, Ld, light.position, lit, b, nh, w);
  // nh^shininess (shininess_power: squaring for whole exponents), pixel-parallel.
  double pw[kShadeBatch];
  const double e = sh.shininess;
  if (e >= 0 && e <= 4096 && e == std::floor(e)) {
    double base[kShadeBatch];
    for (int i = 0; i < n; ++i) pw[i] = 1, base[i] = nh[i];
    for (unsigned k = unsigned(e); k; k >>= 1) {
      if (k & 1)
        for (int i = 0; i < n; ++i) pw[i] *= base[i];
      for (int i = 0; i < n; ++i) base[i] *= base[i];
    }
  } else {
    for (int i = 0; i < n; ++i) pw[i] = w[i] != 0 ? std::pow(nh[i], e) : 0.0;
  }
  for (int i = 0; i < n; ++i) b.specular[i] += w[i] != 0 ? w[i] * pw[i] : 0.0;
}

void surface_colours(const ShadeBatch& b, double ambient, float rgb[3][kShadeBatch]) {
  const int n = b.n;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < n; ++i) {
      double c = double(b.base[k][i]) * (ambient + b.diffuse[i]) + b.specular[i];
      c = c < 0.0 ? 0.0 : c;  // std::clamp's order: NaN stays
      c = 1.0 < c ? 1.0 : c;
      rgb[k][i] = float(c);
    }
}

}  // namespace zs
