#include "render/spheres/sphere_visibility.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cfloat>
#include <chrono>
#include <memory>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "lighting/occlusion_map.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;

// The occlusion map's texel: s×s pixels (occlusion_map.h). Drawing the discs
// costs their area in texels, and a texel only takes a disc that covers all
// of it: small spheres on screen want one texel per pixel, large ones lose
// little with coarser texels and cost far less to draw. So s is a quarter of
// the on-screen radius that splits a sample of the discs' area in half (at
// least 1), and the map is at most 1024 texels a side.
uint32_t occlusion_block(const SphereGrid& g, const View& view, const std::vector<uint32_t>& cells) {
  std::vector<double> rho;
  uint64_t total = 0;
  for (uint32_t k : cells) total += g.count(k);
  const uint64_t step = std::max<uint64_t>(1, total / 1024);
  uint64_t seen = 0;
  for (uint32_t k : cells)
    for (uint64_t e = g.offset[k]; e < g.offset[k + 1]; ++e, ++seen) {
      if (seen % step) continue;
      const glm::dvec3 c = to_camera(view, g.centre[e]);
      if (!(c.z - g.radius[e] > 0)) continue;
      rho.push_back(view.scale_x() * g.radius[e] / (view.perspective() ? c.z : 1.0));
    }
  if (rho.empty()) return 1;
  // The radius below which half of the discs' area lies: the drawing cost
  // is in the large discs.
  std::sort(rho.begin(), rho.end());
  double area = 0, half = 0;
  for (double r : rho) area += r * r;
  double r_half = rho.back();
  for (double r : rho)
    if ((half += r * r) >= area / 2) {
      r_half = r;
      break;
    }
  return uint32_t(std::clamp(std::floor(r_half / 4), 1.0, 64.0));
}
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
    if (!std::isfinite(X) || !std::isfinite(Y)) return false;  // (a fuzzing finding: NaN corners)
    xmin = std::min(xmin, X), xmax = std::max(xmax, X), ymin = std::min(ymin, Y), ymax = std::max(ymax, Y);
  }
  // Widened by a pixel for rounding; still conservative. Clamped so the
  // conversions stay in int's range.
  *i0 = int(std::floor(std::clamp(xmin, -2.0, 2e9))) - 1, *i1 = int(std::ceil(std::clamp(xmax, -2.0, 2e9))) + 1;
  *j0 = int(std::floor(std::clamp(ymin, -2.0, 2e9))) - 1, *j1 = int(std::ceil(std::clamp(ymax, -2.0, 2e9))) + 1;
  *znear = zmin;
  return true;
}

// Steps 1 and 2: view-volume culling, then occlusion culling cells nearest
// first, drawing each surviving cell's discs into `map`.
// The centre discs of entries [e0, e0 + n): screen centre (X, Y), radius rho
// in pixels (0: not an occluder, the sphere is not wholly in front of the
// eye) and depth z. Camera-space centres as in silhouette_boxes_t.
template <bool kPerspective>
void disc_setup(const View& v, const SphereGrid& g, uint64_t e0, uint64_t n, double* __restrict X,
                double* __restrict Y, double* __restrict rho, double* __restrict z) {
  const glm::dvec3 eye = v.eye(), R = v.right(), U = v.up(), F = v.forward();
  const double sx = v.scale_x(), sy = v.scale_y(), ox = v.offset_x(), oy = v.offset_y();
  const double* __restrict centre = &g.centre[e0].x;
  const double* __restrict radius = g.radius.data() + e0;
  for (size_t q = 0; q < n; ++q) {
    const double dx = centre[3 * q] - eye.x, dy = centre[3 * q + 1] - eye.y, dz = centre[3 * q + 2] - eye.z;
    const double cx = dx * R.x + dy * R.y + dz * R.z;
    const double cy = dx * U.x + dy * U.y + dz * U.z;
    const double cz = dx * F.x + dy * F.y + dz * F.z;
    const double inv = kPerspective ? 1.0 / cz : 1.0;
    X[q] = sx * cx * inv + ox;
    Y[q] = oy - sy * cy * inv;
    rho[q] = cz - radius[q] > 0 ? sx * radius[q] * inv : 0.0;
    z[q] = cz;
  }
}

void cull_cells(const SphereGrid& g, const View& view, std::unique_ptr<OcclusionMap>* map_out,
                std::vector<uint32_t>* survivors, VisibilityStats* st, int threads,
                const std::vector<uint8_t>* occluder) {
  VisibilityStats& S = *st;
  tbb::task_arena arena(std::max(1, threads));
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
  const uint32_t side = std::max(view.width(), view.height()), block = occlusion_block(g, view, cells);
  *map_out = std::make_unique<OcclusionMap>(view.width(), view.height(),
                                            std::min<uint32_t>(1024, (side + block - 1) / block));
  OcclusionMap& map = **map_out;
  auto draw = [&](uint64_t q0, uint64_t q1, bool shared) {
    // In chunks: the set-up loop streams through the entries, the drawing
    // loop reads its results back from L1.
    constexpr uint64_t kChunk = OcclusionMap::kBatch;
    double X[kChunk], Y[kChunk], rho[kChunk], z[kChunk];
    uint64_t m = 0;
    for (uint64_t c0 = q0; c0 < q1; c0 += kChunk) {
      const uint64_t n = std::min(kChunk, q1 - c0);
      if (view.perspective())
        disc_setup<true>(view, g, c0, n, X, Y, rho, z);
      else
        disc_setup<false>(view, g, c0, n, X, Y, rho, z);
      if (occluder)  // a translucent sphere hides nothing: no disc
        for (uint64_t q = 0; q < n; ++q) rho[q] = (*occluder)[c0 + q] ? rho[q] : 0.0;
      m += map.write_discs(X, Y, rho, z, n, shared);
    }
    return m;
  };
  // Cells are drawn in groups: each cell of a group is tested against the
  // map of the groups before it, then the group's spheres are drawn, split
  // among the threads. On one thread a group is one cell (each cell sees
  // every cell before it); on more, groups gather at least kGroup spheres so
  // that small cells (a fine grid) still give every thread work, at the
  // price of not culling a cell by the others of its group.
  constexpr uint64_t kGroup = 16384, kTask = 2048;
  const uint64_t group_min = threads == 1 ? 1 : kGroup;
  std::vector<std::pair<uint64_t, uint64_t>> chunks;  // entry ranges of the group's cells
  size_t next = 0;
  while (next < order.size()) {
    chunks.clear();
    uint64_t spheres = 0;
    while (next < order.size() && spheres < group_min) {
      const size_t q = order[next++];
      const uint32_t k = cells[q];
      const CellRange& c = cr[q];
      if (c.bounded && map.hidden(c.i0, c.i1, c.j0, c.j1, c.znear)) {
        ++S.cells_occluded;
        S.spheres_occluded_cells += g.count(k);
        continue;
      }
      survivors->push_back(k);
      spheres += g.count(k);
      for (uint64_t e = g.offset[k]; e < g.offset[k + 1]; e += kTask)
        chunks.push_back({e, std::min(e + kTask, g.offset[k + 1])});
    }
    // The group's spheres become occluders: the disc through each centre,
    // for the spheres wholly in front of the eye (plane). Threads draw
    // disjoint chunks at once; a texel takes the minimum of its discs
    // (occlusion_map.h), so the map does not depend on the split.
    if (threads == 1 || chunks.size() < 2) {
      for (const auto& ch : chunks) S.occluders += draw(ch.first, ch.second, false);
      continue;
    }
    std::atomic<uint64_t> drawn{0};
    arena.execute([&] {
      tbb::parallel_for(size_t(0), chunks.size(),
                        [&](size_t i) { drawn += draw(chunks[i].first, chunks[i].second, true); });
    });
    S.occluders += drawn;
  }
  S.ms_occlusion = ms_since(t0);
}

// Pixel-centre boxes (clamped to the image) that hold the silhouettes of a
// chunk of spheres, cheaper than the exact conic: orthographic, the circle's
// box; perspective, for a surface point c + r·n,
// |x/z − cx/cz| = r·|nx·cz − nz·cx| / (cz·(cz + r·nz)) ≤ r·√(cx² + cz²) / (cz·(cz − r))
// by Cauchy–Schwarz (and the same in y). state: 1 a box, 0 no pixel centre
// of the image in it, -1 no finite bound or not wholly in front of the eye
// (the caller takes the exact path).
struct BoxChunk {
  static constexpr uint32_t kSize = 256;
  double cx[kSize], cy[kSize], cz[kSize];
  int32_t i0[kSize], i1[kSize], j0[kSize], j1[kSize];
  int32_t state[kSize];
};

template <bool kPerspective>
void silhouette_boxes_t(const View& v, const SphereGrid& g, uint64_t e0, uint32_t m, BoxChunk* out) {
  const glm::dvec3 eye = v.eye(), R = v.right(), U = v.up(), F = v.forward();
  const double sx = v.scale_x(), sy = v.scale_y(), ox = v.offset_x(), oy = v.offset_y();
  const double W = v.width(), H = v.height(), eps = 1e-6;
  // The centres as plain doubles (x, y, z per entry): glm's member access
  // gets in the compiler's way. The products and sums are
  // to_camera's, in its order, so the camera-space centre is the same bits
  // the renderer computes (the small-sphere test below relies on it).
  static_assert(sizeof(glm::dvec3) == 3 * sizeof(double));
  const double* centre = &g.centre[e0].x;
  const double* radius = g.radius.data() + e0;
  BoxChunk& b = *out;
  for (size_t q = 0; q < m; ++q) {
    const double dx = centre[3 * q] - eye.x, dy = centre[3 * q + 1] - eye.y, dz = centre[3 * q + 2] - eye.z;
    const double cx = dx * R.x + dy * R.y + dz * R.z;
    const double cy = dx * U.x + dy * U.y + dz * U.z;
    const double cz = dx * F.x + dy * F.y + dz * F.z;
    const double r = radius[q];
    b.cx[q] = cx, b.cy[q] = cy, b.cz[q] = cz;
    double a0, a1, b0, b1;
    if constexpr (kPerspective) {
      const double inv = 1.0 / cz, k = r / (cz * (cz - r));
      const double ha = k * std::sqrt(cx * cx + cz * cz), hb = k * std::sqrt(cy * cy + cz * cz);
      a0 = cx * inv - ha, a1 = cx * inv + ha, b0 = cy * inv - hb, b1 = cy * inv + hb;
    } else {
      a0 = cx - r, a1 = cx + r, b0 = cy - r, b1 = cy + r;
    }
    double X0 = sx * a0 + ox, X1 = sx * a1 + ox;
    double Y0 = oy - sy * b1, Y1 = oy - sy * b0;
    // Finite (NaN fails every comparison) and in front of the eye.
    const bool ok = (cz - r > 0) & (std::fabs(X0) <= DBL_MAX) & (std::fabs(X1) <= DBL_MAX) &
                    (std::fabs(Y0) <= DBL_MAX) & (std::fabs(Y1) <= DBL_MAX);
    X0 = ok ? X0 : 0.0, X1 = ok ? X1 : 0.0, Y0 = ok ? Y0 : 0.0, Y1 = ok ? Y1 : 0.0;
    // Widened for rounding, as the exact range is.
    const double x0 = std::ceil(std::min(std::max(X0 - eps - 1e-9 * std::fabs(X0), -1.0), W));
    const double x1 = std::floor(std::min(std::max(X1 + eps + 1e-9 * std::fabs(X1), -1.0), W));
    const double y0 = std::ceil(std::min(std::max(Y0 - eps - 1e-9 * std::fabs(Y0), -1.0), H));
    const double y1 = std::floor(std::min(std::max(Y1 + eps + 1e-9 * std::fabs(Y1), -1.0), H));
    const int32_t i0 = int32_t(std::max(x0, 0.0)), i1 = int32_t(std::min(x1, W - 1));
    const int32_t j0 = int32_t(std::max(y0, 0.0)), j1 = int32_t(std::min(y1, H - 1));
    b.i0[q] = i0, b.i1[q] = i1, b.j0[q] = j0, b.j1[q] = j1;
    b.state[q] = ok ? int32_t((i0 <= i1) & (j0 <= j1)) : -1;
  }
}

void silhouette_boxes(const View& v, const SphereGrid& g, uint64_t e0, uint32_t m, BoxChunk* out) {
  if (v.perspective())
    silhouette_boxes_t<true>(v, g, e0, m, out);
  else
    silhouette_boxes_t<false>(v, g, e0, m, out);
}

}  // namespace

CameraPlane camera_plane(const View& v) {
  CameraPlane c;
  c.perspective = v.perspective();
  c.sx = v.scale_x(), c.sy = v.scale_y(), c.ox = v.offset_x(), c.oy = v.offset_y();
  return c;
}

std::vector<uint32_t> visible_spheres(const SphereSet& s, const SphereGrid& g, const View& view, bool culling,
                                      VisibilityStats* st, int threads, const std::vector<uint8_t>* occluder) {
  VisibilityStats local;
  VisibilityStats& S = st ? *st : local;
  S = {};
  S.cells = g.cells();
  const CameraPlane cam = camera_plane(view);
  const Viewport image{0, 0, int(view.width()), int(view.height())};
  std::vector<uint32_t> out;
  // Entry e's sphere on screen: its set-up, camera-space centre and pixel range.
  auto on_screen = [&](uint64_t e, glm::dvec3* c, int* i0, int* i1, int* j0, int* j1) {
    *c = to_camera(view, g.centre[e]);
    const SphereSetup su = setup_sphere(cam, c->x, c->y, c->z, g.radius[e]);
    return sphere_pixel_range(su, image, i0, i1, j0, j1);
  };
  std::vector<uint32_t> survivors;  // cells whose spheres are tested one by one, in visiting order
  std::unique_ptr<OcclusionMap> map;
  if (!culling) {
    for (uint32_t k = 0; k < g.cells(); ++k)
      if (g.count(k) > 0) survivors.push_back(k);
  } else {
    cull_cells(g, view, &map, &survivors, &S, threads, occluder);
  }

  // 3. The pyramid test per sphere of the surviving cells, cells in parallel;
  // the survivors keep the cells' order whatever the thread count.
  auto t0 = Clock::now();
  if (map) {
    map->build_pyramid();
    S.map_bytes = map->bytes();
  }
  std::vector<std::vector<uint32_t>> kept(survivors.size());
  tbb::combinable<std::array<uint64_t, 3>> counts([] { return std::array<uint64_t, 3>{0, 0, 0}; });
  tbb::enumerable_thread_specific<BoxChunk> chunk;
  tbb::task_arena arena(std::max(1, threads));
  arena.execute([&] {
    tbb::parallel_for(size_t(0), survivors.size(), [&](size_t q) {
      const uint32_t k = survivors[q];
      std::array<uint64_t, 3>& n = counts.local();  // offscreen, pyramid-culled, pixel-culled
      for (uint64_t c0 = g.offset[k]; c0 < g.offset[k + 1]; c0 += BoxChunk::kSize) {
        const uint32_t m = uint32_t(std::min<uint64_t>(BoxChunk::kSize, g.offset[k + 1] - c0));
        // The pyramid first, on a cheap box that holds the silhouette: most
        // spheres of a large set end here. The boxes of a chunk are set up
        // in one branch-free loop.
        if (map) silhouette_boxes(view, g, c0, m, &chunk.local());
        const BoxChunk& b = chunk.local();
        for (uint32_t u = 0; u < m; ++u) {
          const uint64_t e = c0 + u;
          int i0, i1, j0, j1;
          if (map && b.state[u] >= 0) {
            if (b.state[u] == 0) {
              ++n[0];
              continue;
            }
            i0 = b.i0[u], i1 = b.i1[u], j0 = b.j0[u], j1 = b.j1[u];
            const double cx = b.cx[u], cy = b.cy[u], cz = b.cz[u], R = g.radius[e];
            if (map->hidden_pyramid(i0, i1, j0, j1, cz - R)) {
              ++n[1];
              continue;
            }
            if ((i1 - i0 + 1) * (j1 - j0 + 1) <= kSmallSphereBox) {
              // Small on screen (most spheres of a large set): each pixel
              // centre of the box gets the renderer's own exact hit. No hit:
              // the sphere draws nothing. Every hit behind the map there:
              // it wins no pixel (the map is never nearer than the image's
              // nearest surface). Either way nothing of it reaches the image.
              const SphereSetup su = setup_sphere(cam, cx, cy, cz, R);
              bool hit_any = false, seen = false;
              for (int j = j0; j <= j1 && !seen; ++j)
                for (int i = i0; i <= i1; ++i) {
                  SphereHit h;
                  if (!sphere_hit(su, double(i), double(j), &h)) continue;
                  hit_any = true;
                  if (!map->hidden_at(i, j, h.t)) {
                    seen = true;
                    break;
                  }
                }
              if (!seen) {
                ++n[hit_any ? 2 : 0];
                continue;
              }
              kept[q].push_back(uint32_t(e));
              continue;
            }
          }
          glm::dvec3 c;
          if (!on_screen(e, &c, &i0, &i1, &j0, &j1)) {
            ++n[0];
            continue;
          }
          kept[q].push_back(uint32_t(e));
        }
      }
    });
  });
  counts.combine_each([&](const std::array<uint64_t, 3>& n) {
    S.spheres_offscreen += n[0];
    S.spheres_pyramid_culled += n[1];
    S.spheres_pixel_culled += n[2];
  });
  size_t total = 0;
  for (const auto& v : kept) total += v.size();
  out.reserve(total);
  for (const auto& v : kept) out.insert(out.end(), v.begin(), v.end());
  S.ms_pyramid = ms_since(t0);
  S.spheres_visible = out.size();
  return out;
}

}  // namespace zs
