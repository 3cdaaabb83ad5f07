// Small analytic meshes for tests: structured boxes split 5 tets per hex,
// optionally with cells removed (cavities, gaps) and a scalar field.
#pragma once

#include <algorithm>
#include <functional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>

#include "base/view/camera.h"
#include "base/view/clip_region.h"
#include "raster/image.h"
#include "render/volume/render_settings.h"
#include "base/optics/transfer_function.h"

#include "geometry/tets/hex_split.h"
#include "geometry/tets/tet_mesh.h"

namespace zs::test {

// n.x × n.y × n.z cells over [lo, hi]; keep(i, j, k) chooses cells;
// scalar(p) gives the point scalar.
inline TetMesh box_mesh(glm::ivec3 n, glm::dvec3 lo, glm::dvec3 hi,
                        const std::function<double(const glm::dvec3&)>& scalar,
                        const std::function<bool(int, int, int)>& keep = nullptr) {
  TetMesh m;
  const uint32_t nx = n.x + 1, ny = n.y + 1;
  for (int k = 0; k <= n.z; ++k)
    for (int j = 0; j <= n.y; ++j)
      for (int i = 0; i <= n.x; ++i) {
        const glm::dvec3 t{double(i) / n.x, double(j) / n.y, double(k) / n.z};
        const glm::dvec3 p = lo + t * (hi - lo);
        m.points.push_back(p);
        m.scalars.push_back(scalar(p));
      }
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i)
        if (!keep || keep(i, j, k)) append_hex_5tets(grid_hex(i, j, k, nx, ny), ((i + j + k) & 1) != 0, m.tets);
  m.scalar_name = "test";
  return m;
}

// Appends mesh b to a (points renumbered).
inline void append_mesh(TetMesh& a, const TetMesh& b) {
  const uint32_t base = uint32_t(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  a.scalars.insert(a.scalars.end(), b.scalars.begin(), b.scalars.end());
  for (Tet t : b.tets) {
    for (auto& v : t) v += base;
    a.tets.push_back(t);
  }
}

// Length of the ray o + t·d (t > 0) inside the box [lo, hi] (slab method),
// and inside the clip region.
inline double box_chord(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi, const ClipRegion& clip = {}) {
  double t0 = 0, t1 = 1e300;
  double c0, c1;
  if (!clip.interval(o, d, &c0, &c1)) return 0;
  t0 = std::max(t0, c0), t1 = std::min(t1, c1);
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return 0;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 ? t1 - t0 : 0;
}

// The ray through pixel centre (i, j), straight from the scene spec (kept
// independent of the renderers' View class on purpose).
inline void spec_ray(const Camera& c, uint32_t W, uint32_t H, int i, int j, glm::dvec3* o, glm::dvec3* d) {
  const glm::dvec3 f = glm::normalize(c.target - c.eye);
  const glm::dvec3 r = glm::normalize(glm::cross(f, c.up));
  const glm::dvec3 u = glm::cross(r, f);
  const double a = (i + 0.5) / W - 0.5, b = 0.5 - (j + 0.5) / H;
  if (c.projection == Projection::Orthographic) {
    *o = c.eye + a * c.height * W / H * r + b * c.height * u;
    *d = f;
  } else {
    const double t = std::tan(c.fov_y * M_PI / 360.0);
    *o = c.eye;
    *d = glm::normalize(f + a * 2 * t * W / H * r + b * 2 * t * u);
  }
}

// Entry and exit of the ray o + t·d (t > 0) in the box [lo, hi]; false if it
// misses (the slab method, as box_chord).
inline bool box_span(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi, double* t0, double* t1) {
  *t0 = 0, *t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    *t0 = std::max(*t0, ta);
    *t1 = std::min(*t1, tb);
  }
  return *t1 > *t0;
}

// Cell data in two regions: a box whose cells left of the plane x = x_mid
// (a plane of cell boundaries) carry one value and the others another. The
// closed form of a ray through it: two constant segments, front to back,
// each I = c·(1 - T), T = exp(-tau·L) with tau = -ln(1 - a)/unit.
struct TwoRegions {
  glm::dvec3 lo{-1.0, -0.7, -0.5}, hi{1.0, 0.7, 0.5};
  glm::ivec3 cells{6, 5, 4};
  double value[2] = {0.25, 0.75};
  double color[2][3] = {{0.9, 0.3, 0.1}, {0.1, 0.4, 0.95}};
  double alpha[2] = {0.5, 0.15};
  double unit = 0.8;
  double x_mid() const { return lo.x + (hi.x - lo.x) * (cells.x / 2) / cells.x; }
  TetMesh mesh() const {
    TetMesh m = box_mesh(cells, lo, hi, [](const glm::dvec3&) { return 0.0; });
    m.scalars.clear();
    for (const Tet& t : m.tets) {
      const double cx = (m.points[t[0]].x + m.points[t[1]].x + m.points[t[2]].x + m.points[t[3]].x) / 4;
      m.cell_scalars.push_back(cx < x_mid() ? value[0] : value[1]);
    }
    return m;
  }
  TransferFunction tf() const {
    return TransferFunction({{value[0], color[0][0], color[0][1], color[0][2]},
                             {value[1], color[1][0], color[1][1], color[1][2]}},
                            {{value[0], alpha[0]}, {value[1], alpha[1]}}, unit);
  }
  // Premultiplied RGBA of the ray o + t·d, t > 0 (transparent background),
  // the part of it the clip region keeps.
  void expected(glm::dvec3 o, glm::dvec3 d, double out[4], const ClipRegion& clip = {}) const {
    glm::dvec3 hi0 = hi, lo1 = lo;
    hi0.x = lo1.x = x_mid();
    struct Piece {
      double t0, t1;
      int r;
    } p[2];
    int n = 0;
    double t0, t1;
    if (box_span(o, d, lo, hi0, &t0, &t1)) p[n++] = {t0, t1, 0};
    if (box_span(o, d, lo1, hi, &t0, &t1)) p[n++] = {t0, t1, 1};
    if (n == 2 && p[1].t0 < p[0].t0) std::swap(p[0], p[1]);
    double c0, c1;
    if (!clip.interval(o, d, &c0, &c1)) n = 0;
    for (int k = 0; k < n; ++k) p[k].t0 = std::max(p[k].t0, c0), p[k].t1 = std::max(p[k].t0, std::min(p[k].t1, c1));
    double T = 1;
    out[0] = out[1] = out[2] = 0;
    for (int k = 0; k < n; ++k) {
      const int r = p[k].r;
      const double Tk = std::exp(std::log(1 - alpha[r]) / unit * (p[k].t1 - p[k].t0));
      for (int c = 0; c < 3; ++c) out[c] += T * color[r][c] * (1 - Tk);
      T *= Tk;
    }
    out[3] = 1 - T;
  }
  // The largest difference of `img` from expected() over every pixel's ray
  // (rs's camera and clip region; transparent background).
  double worst(const Image& img, const RenderSettings& rs) const {
    double w = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        double want[4];
        expected(o, d, want, rs.clip);
        for (int k = 0; k < 4; ++k) w = std::max(w, std::abs(img.at(i, j)[k] - want[k]));
      }
    return w;
  }
};

// The oblique camera the engine and reference tests share.
inline RenderSettings settings(uint32_t W, uint32_t H, Projection proj, TransferFunction tf) {
  RenderSettings rs;
  rs.width = W;
  rs.height = H;
  rs.camera.projection = proj;
  rs.camera.eye = {2.5, 1.7, 4.0};
  rs.camera.target = {0.1, -0.05, 0.0};
  rs.camera.up = {0, 1, 0};
  rs.camera.height = 3.2;
  rs.camera.fov_y = 40;
  rs.tf = std::move(tf);
  return rs;
}

// Reference: march the ray through the box with fine midpoint steps.
inline void march_box_ray(const TransferFunction& tf, const std::function<double(const glm::dvec3&)>& s, glm::dvec3 o,
                   glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi, double out[4]) {
  double t0 = 0, t1 = 1e300;
  for (int ax = 0; ax < 3; ++ax) {
    double ta = (lo[ax] - o[ax]) / d[ax], tb = (hi[ax] - o[ax]) / d[ax];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  double C[3] = {0, 0, 0}, T = 1;
  if (t1 > t0) {
    const int n = 20000;
    const double dt = (t1 - t0) / n;
    for (int k = 0; k < n; ++k) {
      const double sv = s(o + (t0 + (k + 0.5) * dt) * d);
      const double tau = tf.extinction(sv);
      const auto c = tf.color(sv);
      const double step_T = std::exp(-tau * dt);
      for (int q = 0; q < 3; ++q) C[q] += T * c[q] * (1 - step_T);
      T *= step_T;
    }
  }
  out[0] = C[0], out[1] = C[1], out[2] = C[2], out[3] = 1 - T;
}

}  // namespace zs::test
