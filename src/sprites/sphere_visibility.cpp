#include "sprites/sphere_visibility.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "sprites/occlusion_map.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Plane {
  glm::dvec3 n;  // points into the view volume
  double d;      // n·p + d ≥ 0 inside (p relative to the eye)
};

// The view volume's planes: the image rectangle's edges (not the outer pixel
// centres: conservative) and the eye plane (only positive depth is drawn).
std::array<Plane, 5> view_planes(const View& v) {
  const double A = v.width() / (2 * v.scale_x()), B = v.height() / (2 * v.scale_y());
  const glm::dvec3 r = v.right(), u = v.up(), f = v.forward();
  if (v.perspective())
    return {Plane{f, 0}, Plane{r + A * f, 0}, Plane{-r + A * f, 0}, Plane{u + B * f, 0}, Plane{-u + B * f, 0}};
  return {Plane{f, 0}, Plane{r, A}, Plane{-r, A}, Plane{u, B}, Plane{-u, B}};
}

// Algorithm 3.1: the box lies wholly behind the plane (its p-vertex, the
// corner farthest along n, is outside). A small margin keeps rounding from
// culling a box that touches the plane.
bool box_behind(const Plane& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 v(p.n.x >= 0 ? hi.x : lo.x, p.n.y >= 0 ? hi.y : lo.y, p.n.z >= 0 ? hi.z : lo.z);
  const double dist = glm::dot(p.n, v) + p.d;
  const double scale = std::abs(p.n.x * v.x) + std::abs(p.n.y * v.y) + std::abs(p.n.z * v.z) + std::abs(p.d);
  return dist < -1e-9 * scale;
}

// Screen pixel-centre range of a camera-space box and its nearest depth;
// false when it cannot be bounded (perspective box reaching the eye plane).
bool box_screen_range(const View& v, const glm::dvec3& lo, const glm::dvec3& hi, int* i0, int* i1, int* j0, int* j1,
                      double* znear) {
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, zmin = INFINITY;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 p((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
    const glm::dvec3 c = to_camera(v, p);
    zmin = std::min(zmin, c.z);
    double a = c.x, b = c.y;
    if (v.perspective()) {
      if (!(c.z > 0)) return false;
      a /= c.z, b /= c.z;
    }
    const double X = v.scale_x() * a + v.offset_x(), Y = v.offset_y() - v.scale_y() * b;
    xmin = std::min(xmin, X), xmax = std::max(xmax, X), ymin = std::min(ymin, Y), ymax = std::max(ymax, Y);
  }
  if (!(xmax - xmin < 4e9 && ymax - ymin < 4e9)) return false;
  // Widened by a pixel for rounding; still conservative.
  *i0 = int(std::floor(std::max(xmin, -2.0))) - 1, *i1 = int(std::ceil(std::min(xmax, 2e9))) + 1;
  *j0 = int(std::floor(std::max(ymin, -2.0))) - 1, *j1 = int(std::ceil(std::min(ymax, 2e9))) + 1;
  *znear = zmin;
  return true;
}

}  // namespace

CameraPlane camera_plane(const View& v) {
  CameraPlane c;
  c.perspective = v.perspective();
  c.sx = v.scale_x(), c.sy = v.scale_y(), c.ox = v.offset_x(), c.oy = v.offset_y();
  return c;
}

std::vector<uint32_t> visible_spheres(const SphereSet& s, const SphereGrid& g, const View& view, bool culling,
                                      VisibilityStats* st) {
  VisibilityStats local;
  VisibilityStats& S = st ? *st : local;
  S = {};
  S.cells = g.cells();
  const CameraPlane cam = camera_plane(view);
  const Viewport image{0, 0, int(view.width()), int(view.height())};
  std::vector<uint32_t> out;
  auto on_screen = [&](uint32_t id, SphereSetup* su, int* i0, int* i1, int* j0, int* j1) {
    const glm::dvec3 c = to_camera(view, s.centres[id]);
    *su = setup_sphere(cam, c.x, c.y, c.z, s.radii[id]);
    return sphere_pixel_range(*su, image, i0, i1, j0, j1);
  };
  if (!culling) {
    for (uint32_t k = 0; k < g.cells(); ++k)
      for (uint64_t e = g.offset[k]; e < g.offset[k + 1]; ++e) {
        SphereSetup su;
        int i0, i1, j0, j1;
        if (on_screen(g.ids[e], &su, &i0, &i1, &j0, &j1)) out.push_back(g.ids[e]);
        else ++S.spheres_offscreen;
      }
    S.spheres_visible = out.size();
    return out;
  }

  // 1. View-volume culling of the cells.
  auto t0 = Clock::now();
  const auto planes = view_planes(view);
  std::vector<uint32_t> cells;
  for (uint32_t k = 0; k < g.cells(); ++k) {
    if (g.count(k) == 0) {
      ++S.cells_empty;
      continue;
    }
    const glm::dvec3 lo = g.lo[k] - view.eye(), hi = g.hi[k] - view.eye();
    bool behind = false;
    for (const Plane& p : planes) behind = behind || box_behind(p, lo, hi);
    if (behind) {
      ++S.cells_view_culled;
      S.spheres_view_culled += g.count(k);
    } else {
      cells.push_back(k);
    }
  }
  S.ms_view = ms_since(t0);

  // 2. Occlusion culling, cells nearest first.
  t0 = Clock::now();
  struct CellRange {
    int i0, i1, j0, j1;
    double znear;
    bool bounded;
  };
  std::vector<CellRange> cr(cells.size());
  for (size_t q = 0; q < cells.size(); ++q) {
    const uint32_t k = cells[q];
    CellRange& c = cr[q];
    c.bounded = box_screen_range(view, g.lo[k], g.hi[k], &c.i0, &c.i1, &c.j0, &c.j1, &c.znear);
    if (!c.bounded) c.znear = -INFINITY;
  }
  std::vector<size_t> order(cells.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cr[a].znear < cr[b].znear; });
  OcclusionMap map(view.width(), view.height());
  std::vector<uint32_t> survivors;  // cells, in visiting order
  for (size_t q : order) {
    const uint32_t k = cells[q];
    const CellRange& c = cr[q];
    if (c.bounded && map.hidden(c.i0, c.i1, c.j0, c.j1, c.znear)) {
      ++S.cells_occluded;
      S.spheres_occluded_cells += g.count(k);
      continue;
    }
    survivors.push_back(k);
    // Its spheres become occluders: the disc through each centre, for the
    // spheres wholly in front of the eye (plane).
    for (uint64_t e = g.offset[k]; e < g.offset[k + 1]; ++e) {
      const uint32_t id = g.ids[e];
      const glm::dvec3 cc = to_camera(view, s.centres[id]);
      const double R = s.radii[id];
      if (!(cc.z - R > 0)) continue;
      const double inv = view.perspective() ? 1.0 / cc.z : 1.0;
      map.write_disc(view.scale_x() * cc.x * inv + view.offset_x(), view.offset_y() - view.scale_y() * cc.y * inv,
                     view.scale_x() * R * inv, cc.z);
      ++S.occluders;
    }
  }
  S.ms_occlusion = ms_since(t0);

  // 3. The pyramid test per sphere of the surviving cells.
  t0 = Clock::now();
  map.build_pyramid();
  S.map_bytes = map.bytes();
  for (uint32_t k : survivors)
    for (uint64_t e = g.offset[k]; e < g.offset[k + 1]; ++e) {
      const uint32_t id = g.ids[e];
      SphereSetup su;
      int i0, i1, j0, j1;
      if (!on_screen(id, &su, &i0, &i1, &j0, &j1)) {
        ++S.spheres_offscreen;
        continue;
      }
      const double znear = to_camera(view, s.centres[id]).z - s.radii[id];
      if (znear > 0 && map.hidden_pyramid(i0, i1, j0, j1, znear)) {
        ++S.spheres_pyramid_culled;
        continue;
      }
      out.push_back(id);
    }
  S.ms_pyramid = ms_since(t0);
  S.spheres_visible = out.size();
  return out;
}

}  // namespace zs
