#include "lighting/visible_region.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

void visible_region_points(const TriangleMesh& m, const View& view, double z_near, bool cull_back,
                           const std::function<void(const glm::dvec3&)>& point) {
  const glm::dvec3 eye = view.eye(), f = view.forward(), r = view.right(), u = view.up();
  // Camera-plane half extents of the image's pixel footprint (edges at
  // −0.5 and W − 0.5): world units (orthographic) or tangents (perspective).
  const double hx = 0.5 * view.width() / view.scale_x(), hy = 0.5 * view.height() / view.scale_y();
  const bool persp = view.perspective();
  // Planes as a·(x, y, z) + d >= 0 in camera space.
  struct Plane {
    double a, b, c, d;
  };
  const Plane planes[5] = {
      {0, 0, 1, -z_near},
      {-1, 0, persp ? hx : 0, persp ? 0 : hx},
      {1, 0, persp ? hx : 0, persp ? 0 : hx},
      {0, -1, persp ? hy : 0, persp ? 0 : hy},
      {0, 1, persp ? hy : 0, persp ? 0 : hy},
  };
  glm::dvec3 a[9], b[9];
  for (size_t t = 0; t < m.num_tris(); ++t) {
    int n = 3;
    if (cull_back && !(m.two_sided.size() == m.num_tris() && m.two_sided[t])) {
      // Back-facing: the eye is behind the triangle's plane (world space:
      // the camera basis r, u, f is left-handed).
      const glm::dvec3 nrm = face_normal(m, t);
      const double s = persp ? glm::dot(nrm, eye - m.points[m.tris[t][0]]) : -glm::dot(nrm, f);
      if (!(s > 0)) continue;
    }
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 d = m.points[m.tris[t][k]] - eye;
      a[k] = {glm::dot(d, r), glm::dot(d, u), glm::dot(d, f)};
    }
    // Most triangles lie wholly inside every plane (their own points are the
    // region's) or wholly outside one (nothing); only the rest are clipped.
    bool inside = true, outside = false;
    for (const Plane& pl : planes) {
      int in = 0;
      for (int k = 0; k < 3; ++k) in += pl.a * a[k].x + pl.b * a[k].y + pl.c * a[k].z + pl.d >= 0;
      inside &= in == 3;
      outside |= in == 0;
    }
    if (outside) continue;
    if (inside) {
      for (int k = 0; k < 3; ++k) point(m.points[m.tris[t][k]]);
      continue;
    }
    for (const Plane& pl : planes) {
      int o = 0;
      for (int k = 0; k < n; ++k) {
        const glm::dvec3 &p = a[k], &q = a[(k + 1) % n];
        const double dp = pl.a * p.x + pl.b * p.y + pl.c * p.z + pl.d;
        const double dq = pl.a * q.x + pl.b * q.y + pl.c * q.z + pl.d;
        if (dp >= 0) b[o++] = p;
        if ((dp >= 0) != (dq >= 0) && o < 9) b[o++] = p + (q - p) * (dp / (dp - dq));
      }
      n = o;
      for (int k = 0; k < n; ++k) a[k] = b[k];
      if (n == 0) break;
    }
    for (int k = 0; k < n; ++k) point(eye + a[k].x * r + a[k].y * u + a[k].z * f);
  }
}

}  // namespace zs
