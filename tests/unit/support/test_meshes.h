// Small analytic meshes for tests: structured boxes split 5 tets per hex,
// optionally with cells removed (cavities, gaps) and a scalar field.
#pragma once

#include <algorithm>
#include <functional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>

#include "base/view/camera.h"
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

// Length of the ray o + t·d (t > 0) inside the box [lo, hi] (slab method).
inline double box_chord(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
  double t0 = 0, t1 = 1e300;
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
