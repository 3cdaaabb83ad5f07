#include "surface/shade_batch.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

namespace {

// glm's order of operations (dot: (x + y) + z; normalize: v·(1/√(v·v))), so
// the batch gives the bits one-pixel-at-a-time code gives.
inline double dot3(double ax, double ay, double az, double bx, double by, double bz) {
  return (ax * bx + ay * by) + az * bz;
}

template <bool persp>
void hit_loop(const View& view, double Y, const double* Ax, const double* Ay, const double* Az, const double* Bx,
              const double* By, const double* Bz, const double* Cx, const double* Cy, const double* Cz, double* flip,
              ShadeBatch& b) {
  const glm::dvec3 E = view.eye(), F = view.forward(), R = view.right(), U = view.up();
  const double sxv = view.scale_x(), syv = view.scale_y(), oxv = view.offset_x(), oyv = view.offset_y();
  const double bY = (oyv - Y) / syv;
  for (int i = 0; i < b.n; ++i) {
    // The pixel's ray (View::ray).
    const double a = (b.X[i] - oxv) / sxv;
    double ox, oy, oz, dx, dy, dz, rlf;
    if constexpr (persp) {
      ox = E.x, oy = E.y, oz = E.z;
      const double wx = (F.x + a * R.x) + bY * U.x, wy = (F.y + a * R.y) + bY * U.y, wz = (F.z + a * R.z) + bY * U.z;
      const double inv = 1.0 / std::sqrt(dot3(wx, wy, wz, wx, wy, wz));
      dx = wx * inv, dy = wy * inv, dz = wz * inv;
      rlf = std::sqrt(1.0 + a * a + bY * bY);
    } else {
      ox = (E.x + a * R.x) + bY * U.x, oy = (E.y + a * R.y) + bY * U.y, oz = (E.z + a * R.z) + bY * U.z;
      dx = F.x, dy = F.y, dz = F.z;
      rlf = 1.0;
    }
    // The exact hit with the triangle's plane; a ray parallel to it (a sliver
    // seen edge-on) takes the rasterized depth.
    const double e1x = Bx[i] - Ax[i], e1y = By[i] - Ay[i], e1z = Bz[i] - Az[i];
    const double e2x = Cx[i] - Ax[i], e2y = Cy[i] - Ay[i], e2z = Cz[i] - Az[i];
    const double fx = e1y * e2z - e2y * e1z, fy = e1z * e2x - e2z * e1x, fz = e1x * e2y - e2x * e1y;
    const double den = dot3(dx, dy, dz, fx, fy, fz);
    const double th = dot3(Ax[i] - ox, Ay[i] - oy, Az[i] - oz, fx, fy, fz) / den;
    const bool good = (den != 0) & (std::abs(den) < INFINITY);
    const double t = good ? th : b.zbuf[i] * rlf;
    const double px = ox + dx * t, py = oy + dy * t, pz = oz + dz * t;
    b.px[i] = px, b.py[i] = py, b.pz[i] = pz;
    const double n2 = dot3(fx, fy, fz, fx, fy, fz);
    const double ig = 1.0 / std::sqrt(n2);
    double gx = fx * ig, gy = fy * ig, gz = fz * ig;
    const bool flipped = dot3(gx, gy, gz, dx, dy, dz) > 0;
    const double fl = flipped ? -1.0 : 1.0;
    gx *= fl, gy *= fl, gz *= fl;  // −x = −1·x exactly
    flip[i] = fl;
    b.gx[i] = gx, b.gy[i] = gy, b.gz[i] = gz;
    b.vx[i] = -dx, b.vy[i] = -dy, b.vz[i] = -dz;
    b.depth[i] = dot3(px - E.x, py - E.y, pz - E.z, F.x, F.y, F.z);
    b.diffuse[i] = 0;
    b.specular[i] = 0;
    b.sx[i] = gx, b.sy[i] = gy, b.sz[i] = gz;
  }
}

}  // namespace

void surface_hits(const View& view, double Y, const TriangleMesh& mesh, ShadingModel model, ShadeBatch& b) {
  const int n = b.n;
  // Gathered corners (and point normals), one array per coordinate.
  double Ax[kShadeBatch], Ay[kShadeBatch], Az[kShadeBatch], Bx[kShadeBatch], By[kShadeBatch], Bz[kShadeBatch],
      Cx[kShadeBatch], Cy[kShadeBatch], Cz[kShadeBatch];
  double N0[3][kShadeBatch], N1[3][kShadeBatch], N2[3][kShadeBatch];
  double flip[kShadeBatch];  // −1 where the face's normal was turned to the eye
  const bool phong = model == ShadingModel::Phong;
  for (int i = 0; i < n; ++i) {
    const auto& t = mesh.tris[b.tri[i]];
    const glm::dvec3 &a = mesh.points[t[0]], &bb = mesh.points[t[1]], &c = mesh.points[t[2]];
    Ax[i] = a.x, Ay[i] = a.y, Az[i] = a.z;
    Bx[i] = bb.x, By[i] = bb.y, Bz[i] = bb.z;
    Cx[i] = c.x, Cy[i] = c.y, Cz[i] = c.z;
    if (phong)
      for (int k = 0; k < 3; ++k) {
        N0[k][i] = mesh.normals[t[0]][k];
        N1[k][i] = mesh.normals[t[1]][k];
        N2[k][i] = mesh.normals[t[2]][k];
      }
  }
  if (view.perspective())
    hit_loop<true>(view, Y, Ax, Ay, Az, Bx, By, Bz, Cx, Cy, Cz, flip, b);
  else
    hit_loop<false>(view, Y, Ax, Ay, Az, Bx, By, Bz, Cx, Cy, Cz, flip, b);
  if (!phong) return;
  for (int i = 0; i < n; ++i) {
    // Barycentrics of the hit, clamped into the triangle, weight the normals.
    const double px = b.px[i], py = b.py[i], pz = b.pz[i];
    const double e1x = Bx[i] - Ax[i], e1y = By[i] - Ay[i], e1z = Bz[i] - Az[i];
    const double e2x = Cx[i] - Ax[i], e2y = Cy[i] - Ay[i], e2z = Cz[i] - Az[i];
    const double fx = e1y * e2z - e2y * e1z, fy = e1z * e2x - e2z * e1x, fz = e1x * e2y - e2x * e1y;
    const double n2 = dot3(fx, fy, fz, fx, fy, fz);
    const double bx = Bx[i] - px, by = By[i] - py, bz = Bz[i] - pz;
    const double cx = Cx[i] - px, cy = Cy[i] - py, cz = Cz[i] - pz;
    const double ax = Ax[i] - px, ay = Ay[i] - py, az = Az[i] - pz;
    double wa = dot3(by * cz - cy * bz, bz * cx - cz * bx, bx * cy - cx * by, fx, fy, fz) / n2;
    double wb = dot3(cy * az - ay * cz, cz * ax - az * cx, cx * ay - ax * cy, fx, fy, fz) / n2;
    wa = wa < 0.0 ? 0.0 : wa;  // std::clamp's order: NaN stays
    wa = 1.0 < wa ? 1.0 : wa;
    wb = wb < 0.0 ? 0.0 : wb;
    wb = 1.0 - wa < wb ? 1.0 - wa : wb;
    const double wc = 1.0 - wa - wb;
    const double nx = (wa * N0[0][i] + wb * N1[0][i]) + wc * N2[0][i];
    const double ny = (wa * N0[1][i] + wb * N1[1][i]) + wc * N2[1][i];
    const double nz = (wa * N0[2][i] + wb * N1[2][i]) + wc * N2[2][i];
    const double len = std::sqrt(dot3(nx, ny, nz, nx, ny, nz));
    const bool ok = (len > 0) & (len < INFINITY);
    // Facing the eye like the geometric normal: flipped with it.
    b.sx[i] = ok ? (flip[i] * nx) / len : b.sx[i];
    b.sy[i] = ok ? (flip[i] * ny) / len : b.sy[i];
    b.sz[i] = ok ? (flip[i] * nz) / len : b.sz[i];
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

}  // namespace zs
