#include "lighting/shadow_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>

#include "raster/tile_loop.h"
#include "raster/triangle_bins.h"
#include "raster/zbuffer_tile.h"
#include "lighting/depth_blocks.h"
#include "lighting/multi_depth.h"
#include "lighting/tiled_depths.h"
#include "lighting/triangle_projection.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// A unit vector perpendicular to f: the world axis least aligned with it,
// crossed (deterministic, so maps never depend on anything but the light).
glm::dvec3 perpendicular(const glm::dvec3& f) {
  const glm::dvec3 a = std::abs(f.x) <= std::abs(f.y) && std::abs(f.x) <= std::abs(f.z) ? glm::dvec3(1, 0, 0)
                       : std::abs(f.y) <= std::abs(f.z)                                 ? glm::dvec3(0, 1, 0)
                                                                                        : glm::dvec3(0, 0, 1);
  return glm::normalize(glm::cross(f, a));
}

// Texels kept free around the receivers' square, so the widest kernel and
// the 3×3 neighbourhood never clamp at a visible point.
constexpr double kPadTexels = 4;

// The PCF box: first offset (relative to the base texel) and width. Odd
// kernels centre on the texel holding p (base = round), even ones on the
// texel corner nearest p (base = floor), so every kernel is centred on p.
struct Kernel {
  int first, width;
  bool odd;
};
Kernel kernel_of(uint32_t k) {
  switch (k) {
    case 4: return {0, 2, false};
    case 9: return {-1, 3, true};
    case 16: return {-1, 4, false};
    default: return {0, 1, true};
  }
}

// How far beyond p's own texel the test reads (R of shadow_map.h).
double reach_texels(const ShadowSettings& s) {
  const double pcf = s.pcf == 16 ? 2 : s.pcf == 1 ? 0 : 1;
  const bool near_depths = s.depths >= 3 || (s.depths == 2 && s.select == DepthSelect::Min);
  return pcf + (near_depths ? 1 : 0);
}

// Triangles that can shadow no point of the scene. A triangle blocks the
// light only for points strictly on the far side of its plane from the light;
// when every corner of the scene's box lies on the light side or within tol
// of the plane (tol = 1e-9 of the diagonal, far below the test's 2^-20·|d|
// storage bias), it shadows nothing. A ground plane under the scene is the
// usual case: it covers most of a map and casts onto nothing.
// Directional lights also skip the faces of closed solids turned from the
// light (m.solid; geometry/triangles/closed_solids.h), counted in *back_faces.
std::vector<uint8_t> non_casters(const TriangleMesh& m, const Light& l, const Bounds& scene, double diag,
                                 uint64_t* count, uint64_t* back_faces) {
  std::vector<uint8_t> skip(m.num_tris(), 0);
  glm::dvec3 box[8];
  for (int c = 0; c < 8; ++c)
    box[c] = {c & 1 ? scene.hi.x : scene.lo.x, c & 2 ? scene.hi.y : scene.lo.y, c & 4 ? scene.hi.z : scene.lo.z};
  uint64_t n = 0, nb = 0;
  const bool solids = l.type == LightType::Directional && m.solid.size() == m.num_tris();
  for (size_t t = 0; t < m.num_tris(); ++t) {
    const glm::dvec3& a = m.points[m.tris[t][0]];
    const glm::dvec3 nrm = face_normal(m, t);
    // Sign of the light side: towards the light from the plane.
    const double side = l.type == LightType::Directional ? -glm::dot(l.direction, nrm) : glm::dot(l.position - a, nrm);
    if (!(side != 0) || !std::isfinite(side)) continue;
    const double tol = 1e-9 * diag * glm::length(nrm);
    bool all = true;
    for (int c = 0; c < 8 && all; ++c) all = (side > 0 ? 1.0 : -1.0) * glm::dot(box[c] - a, nrm) >= -tol;
    if (all) {
      skip[t] = 1;
      ++n;
    } else if (solids && double(m.solid[t]) * side < 0) {  // the fronts face out: side > 0 faces the light
      skip[t] = 1;
      ++nb;
    }
  }
  *count = n;
  *back_faces = nb;
  return skip;
}

}  // namespace

void LightFit::add(const glm::dvec3& p) {
  const double a = glm::dot(p, r), b = glm::dot(p, u);
  lo_r = std::min(lo_r, a);
  hi_r = std::max(hi_r, a);
  lo_u = std::min(lo_u, b);
  hi_u = std::max(hi_u, b);
}

LightFit start_fit(const Light& l) {
  LightFit fit;
  fit.f = glm::normalize(l.type == LightType::Directional ? l.direction : l.target - l.position);
  fit.r = perpendicular(fit.f);
  fit.u = glm::cross(fit.r, fit.f);
  return fit;
}

uint64_t shadow_map_bytes(const ShadowSettings& s) {
  // The map while rendering (float) plus the n-SM.
  return uint64_t(s.map_size) * s.map_size * sizeof(float) * (1 + s.depths);
}

ShadowMap ShadowMap::from_depths(const Light& light, const Camera& frame, uint32_t size, std::vector<float> depths,
                                 const ShadowSettings& s) {
  if (depths.size() != size_t(size) * size) throw std::invalid_argument("ShadowMap::from_depths: size mismatch");
  ShadowMap m;
  m.light_ = light;
  m.s_ = s;
  m.size_ = size;
  m.view_ = std::make_shared<View>(frame, size, size);
  m.texel_ = frame.projection == Projection::Orthographic ? frame.height / size
                                                           : 2 * std::tan(frame.fov_y * M_PI / 360.0) / size;
  TiledDepths centre;
  tile_depths(depths.data(), size, &centre);
  m.finish(std::move(centre));
  return m;
}

ShadowMap ShadowMap::from_tiles(const Light& light, const Camera& frame, TiledDepths centre, const ShadowSettings& s,
                               DepthBlocks blocks) {
  ShadowMap m;
  m.light_ = light;
  m.s_ = s;
  m.size_ = centre.size();
  m.view_ = std::make_shared<View>(frame, m.size_, m.size_);
  m.texel_ = frame.projection == Projection::Orthographic ? frame.height / m.size_
                                                           : 2 * std::tan(frame.fov_y * M_PI / 360.0) / m.size_;
  m.blocks_ = std::move(blocks);
  m.finish(std::move(centre));
  return m;
}

void ShadowMap::finish(TiledDepths centre) {
  to_light_ = to_light(light_, glm::dvec3(0.0));  // directional lights: the same everywhere
  n_ = std::clamp<uint32_t>(s_.depths, 1, kMaxDepths);
  levels_ = n_ * std::max<uint32_t>(1, s_.pcf);
  reach_ = 1 + reach_texels(s_);
  frame_ = make_frame();
  if (blocks_.min.empty()) {
    blocks_.reset(size_);
    for (uint32_t ty = 0; ty < centre.tiles(); ++ty)
      for (uint32_t tx = 0; tx < centre.tiles(); ++tx)
        if (centre.stored(tx, ty))
          fold_block_ranges(centre.tile(tx, ty), kMapTile, tx * kMapTile, ty * kMapTile,
                            std::min(size_, (tx + 1) * kMapTile), std::min(size_, (ty + 1) * kMapTile), blocks_);
  }
  // A lookup reads beyond its first texel (a wider kernel, an n-SM's
  // neighbours: at most 4 texels): one block's widening covers it.
  if (n_ >= 2 || s_.pcf > 1) dilate_block_ranges(blocks_);
  if (n_ == 1) {
    md_ = std::move(centre);
    return;
  }
  tiled_multi_depth(centre, n_, s_.select, &md_);
}

Camera shadow_map_frame(const Light& light, const LightFit& fit0, const Bounds& scene, uint32_t D, double* z_near_out) {
  const double diag = std::max(scene.empty ? 1.0 : scene.diagonal(), 1e-300);
  Camera cam;
  double z_near = 0;
  const LightFit basis = start_fit(light);
  if (light.type == LightType::Directional) {
    LightFit fit = fit0;
    fit.r = basis.r;
    fit.u = basis.u;
    fit.f = basis.f;
    if (fit.empty()) {  // nothing in view: any square will do
      for (int c = 0; c < 8; ++c)
        fit.add({c & 1 ? scene.hi.x : scene.lo.x, c & 2 ? scene.hi.y : scene.lo.y, c & 4 ? scene.hi.z : scene.lo.z});
    }
    double side = std::max({fit.hi_r - fit.lo_r, fit.hi_u - fit.lo_u, 1e-12 * diag});
    side *= D / std::max(1.0, D - 2 * kPadTexels);
    // The eye plane behind every caster along the light direction.
    double lo_f = INFINITY;
    for (int c = 0; c < 8; ++c)
      lo_f = std::min(lo_f, glm::dot(glm::dvec3(c & 1 ? scene.hi.x : scene.lo.x, c & 2 ? scene.hi.y : scene.lo.y,
                                                c & 4 ? scene.hi.z : scene.lo.z),
                                     basis.f));
    cam.projection = Projection::Orthographic;
    cam.eye = basis.r * (0.5 * (fit.lo_r + fit.hi_r)) + basis.u * (0.5 * (fit.lo_u + fit.hi_u)) +
              basis.f * (lo_f - 0.01 * diag);
    cam.target = cam.eye + basis.f;
    cam.up = basis.u;
    cam.height = side;
    z_near = 0;
  } else {
    cam.projection = Projection::Perspective;
    cam.eye = light.position;
    cam.target = light.target;
    cam.up = basis.u;
    cam.fov_y = light.fov_deg;
    z_near = 1e-6 * (diag + glm::length(light.position - scene.centre()));
  }
  *z_near_out = z_near;
  return cam;
}

ShadowMap ShadowMap::build(const TriangleMesh& casters, const Light& light, const LightFit& fit0, const Bounds& scene,
                           const ShadowSettings& s, int threads, ShadowMapStats* stats) {
  ShadowMapStats st;
  const uint32_t D = s.map_size;
  const double diag = std::max(scene.empty ? 1.0 : scene.diagonal(), 1e-300);
  double z_near = 0;
  const Camera cam = shadow_map_frame(light, fit0, scene, D, &z_near);
  ShadowMap m;
  m.light_ = light;
  m.s_ = s;
  m.size_ = D;
  m.view_ = std::make_shared<View>(cam, D, D);
  m.texel_ = light.type == LightType::Directional ? cam.height / D : 2 * std::tan(cam.fov_y * M_PI / 360.0) / D;

  auto t0 = Clock::now();
  ProjectedTriangles pt;
  ProjectCounts pc;
  std::vector<uint8_t> skip;
  if (s.cull_casters && !scene.empty)
    skip = non_casters(casters, light, scene, diag, &st.casters_culled, &st.casters_back_faces);
  project_triangles(casters, *m.view_, {false, true, z_near, skip.empty() ? nullptr : &skip}, &pt, &pc);
  const TileGrid grid{D, D, kMapTile, 1};
  TriangleBins bins;
  bin_triangles(grid, pt.verts, pt.corners, &bins);
  st.ms_project = ms_since(t0);
  st.casters = pt.corners.size();

  t0 = Clock::now();
  struct Tile {
    std::vector<double> db;
    ZBufferScratch scratch;
    ZBufferCounts counts;
    uint64_t covered = 0;
  };
  tbb::enumerable_thread_specific<Tile> tiles;
  // Only tiles with casters are rendered and stored; the rest read +inf (most
  // of a map fitted to the receivers in view, once the ground is culled).
  TiledDepths centre;
  centre.reset(D, 1);
  m.blocks_.reset(D);
  std::vector<uint32_t> busy;
  for (uint32_t t = 0; t < grid.count(); ++t)
    if (bins.end(t) != bins.begin(t)) {
      busy.push_back(t);
      centre.add_tile(t % grid.cols(), t / grid.cols());
    }
  // Each tile renders only the box of its casters (rounded out to whole
  // depth blocks) and writes it straight into its storage, which reads +inf
  // elsewhere; blocks outside the box keep their empty range.
  NullSink sink;
  run_tiles(grid, busy, threads, sink, [&](uint32_t t, const TileRect& r) -> const float* {
    Tile& w = tiles.local();
    double lx = INFINITY, ly = INFINITY, hx = -INFINITY, hy = -INFINITY;
    for (const uint32_t* id = bins.begin(t); id != bins.end(t); ++id)
      for (uint32_t c : pt.corners[*id]) {
        const ScreenVertex& v = pt.verts[c];
        lx = std::min(lx, v.x), hx = std::max(hx, v.x), ly = std::min(ly, v.y), hy = std::max(hy, v.y);
      }
    constexpr int B = 1 << kDepthBlockShift;
    auto clampd = [](double v, int lo, int hi) { return v >= lo ? (v <= hi ? int(v) : hi) : lo; };  // NaN: lo
    const int x0 = clampd(std::floor(lx), int(r.x0), int(r.x1)) & ~(B - 1);
    const int y0 = clampd(std::floor(ly), int(r.y0), int(r.y1)) & ~(B - 1);
    const int x1 = std::min(int(r.x1), (clampd(std::ceil(hx) + 1, int(r.x0), int(r.x1)) + B - 1) & ~(B - 1));
    const int y1 = std::min(int(r.y1), (clampd(std::ceil(hy) + 1, int(r.y0), int(r.y1)) + B - 1) & ~(B - 1));
    float* tile = centre.tile(r.x0 >> kMapTileShift, r.y0 >> kMapTileShift);
    if (x1 <= x0 || y1 <= y0) return tile;
    const size_t bw = size_t(x1 - x0), bh = size_t(y1 - y0);
    w.db.assign(bw * bh, INFINITY);
    const Viewport vp{x0, y0, x1, y1};
    zbuffer_depths(pt.verts, pt.corners, bins.begin(t), size_t(bins.end(t) - bins.begin(t)), pt.perspective, vp,
                   w.db.data(), w.scratch, &w.counts);
    float* at = tile + size_t(y0 - int(r.y0)) * kMapTile + size_t(x0 - int(r.x0));
    for (size_t y = 0; y < bh; ++y) w.covered += round_depths_up(w.db.data() + y * bw, bw, at + y * kMapTile);
    // Tiles are 64 texels, whole blocks: no two tiles fold into one block.
    fold_block_ranges(at, kMapTile, uint32_t(x0), uint32_t(y0), uint32_t(x1), uint32_t(y1), m.blocks_);
    return tile;
  });
  for (const Tile& w : tiles) {
    st.caster_fragments += w.counts.fragments;
    st.texels_covered += w.covered;
  }
  st.ms_raster = ms_since(t0);

  t0 = Clock::now();
  m.finish(std::move(centre));
  st.ms_multi_depth = ms_since(t0);
  st.bytes = m.bytes();
  st.texel = m.texel_;
  st.side = light.type == LightType::Directional ? cam.height : 0.0;
  if (stats) *stats = st;
  return m;
}

double ShadowMap::bias_at(const glm::dvec3& p, const glm::dvec3& n) const {
  return bias_for(view_->depth(p), std::abs(glm::dot(n, to_light(light_, p))));
}


namespace {

inline double dot3(double ax, double ay, double az, double bx, double by, double bz) {
  return (ax * bx + ay * by) + az * bz;  // glm::dot's order
}

// The bias of shadow_map.h at light depth d and cos θ = c (spot: texels
// grow with depth).
template <bool spot>
inline double bias_of(const LookupFrame& F, double d, double c) {
  const double tan_t = c > 0 ? std::min(10.0, std::sqrt(std::max(0.0, 1 - c * c)) / c) : 10.0;
  const double w = spot ? F.texel * d : F.texel;
  return F.bias + F.slope * tan_t * w * F.reach + std::abs(d) * 0x1p-20;  // = ldexp(|d|, -20), no libm call
}

// The arithmetic of a lookup before any map read: cos θ (c), the light
// view's depth (z), the map coordinates and the limit d − bias. Pure
// arithmetic, so the batch below vectorizes it; whether p can be lit at all
// (c > 0, spot cone and z > 0, coordinates not NaN) is checked after.
template <bool spot>
inline void prepare(const LookupFrame& F, const Light& light, double px, double py, double pz, double nx, double ny,
                    double nz, double* c_out, double* z_out, double* X, double* Y, double* lim) {
  double lx = F.lx, ly = F.ly, lz = F.lz;
  if constexpr (spot) {
    const glm::dvec3 l = to_light(light, glm::dvec3(px, py, pz));
    lx = l.x, ly = l.y, lz = l.z;
  }
  const double c = dot3(nx, ny, nz, lx, ly, lz);
  const double dx = px - F.ex, dy = py - F.ey, dz = pz - F.ez;
  const double z = dot3(dx, dy, dz, F.fx, F.fy, F.fz);
  double a = dot3(dx, dy, dz, F.rx, F.ry, F.rz), b = dot3(dx, dy, dz, F.ux, F.uy, F.uz);
  if constexpr (spot) {  // spot maps are perspective, directional ones orthographic
    a /= z;
    b /= z;
  }
  *c_out = c;
  *z_out = z;
  *lim = z - bias_of<spot>(F, z, c);
  // Clamped before the int conversion (a point far off the map reads its edge).
  const double x = a * F.sx + F.ox, y = F.oy - b * F.sy;
  *X = x < -8.0 ? -8.0 : (F.D + 8.0 < x ? F.D + 8.0 : x);  // std::clamp's order: NaN stays
  *Y = y < -8.0 ? -8.0 : (F.D + 8.0 < y ? F.D + 8.0 : y);
}

}  // namespace

LookupFrame ShadowMap::make_frame() const {
  const View& v = *view_;
  LookupFrame F;
  F.ex = v.eye().x, F.ey = v.eye().y, F.ez = v.eye().z;
  F.fx = v.forward().x, F.fy = v.forward().y, F.fz = v.forward().z;
  F.rx = v.right().x, F.ry = v.right().y, F.rz = v.right().z;
  F.ux = v.up().x, F.uy = v.up().y, F.uz = v.up().z;
  F.sx = v.scale_x(), F.sy = v.scale_y(), F.ox = v.offset_x(), F.oy = v.offset_y();
  F.lx = to_light_.x, F.ly = to_light_.y, F.lz = to_light_.z;
  F.bias = s_.bias, F.slope = s_.slope_bias, F.texel = texel_, F.reach = reach_, F.D = double(size_);
  return F;
}

double ShadowMap::bias_for(double d, double c) const {
  return light_.type == LightType::Spot ? bias_of<true>(frame_, d, c) : bias_of<false>(frame_, d, c);
}

// Reads every texel and depth of the kernel (the early outs left it open).
inline uint32_t ShadowMap::count(double X, double Y, double lim) const {
  const Kernel k = kernel_of(s_.pcf);
  const int D = int(size_);
  const int bx = int(k.odd ? std::floor(X + 0.5) : std::floor(X)) + k.first;
  const int by = int(k.odd ? std::floor(Y + 0.5) : std::floor(Y)) + k.first;
  uint32_t lit = 0;
  for (int dy = 0; dy < k.width; ++dy) {
    const int y = std::clamp(by + dy, 0, D - 1);
    for (int dx = 0; dx < k.width; ++dx) {
      const int x = std::clamp(bx + dx, 0, D - 1);
      const float* z = md_.texel(uint32_t(x), uint32_t(y));
      for (uint32_t j = 0; j < n_; ++j) lit += lim <= double(z[j]);
    }
  }
  return lit;
}

uint32_t ShadowMap::lit_count(const glm::dvec3& p, const glm::dvec3& n) const {
  uint32_t out;
  lit_counts(1, &p.x, &p.y, &p.z, &n.x, &n.y, &n.z, &out);
  return out;
}

void ShadowMap::locate(const glm::dvec3& p, const glm::dvec3& n, uint32_t* x, uint32_t* y, double* lim) const {
  double c, z, X, Y;
  if (light_.type == LightType::Spot)
    prepare<true>(frame_, light_, p.x, p.y, p.z, n.x, n.y, n.z, &c, &z, &X, &Y, lim);
  else
    prepare<false>(frame_, light_, p.x, p.y, p.z, n.x, n.y, n.z, &c, &z, &X, &Y, lim);
  const int Dm = int(size_) - 1;
  const int bx = X == X ? int(std::floor(X + 0.5)) : 0, by = Y == Y ? int(std::floor(Y + 0.5)) : 0;
  *x = uint32_t(std::clamp(bx, 0, Dm));
  *y = uint32_t(std::clamp(by, 0, Dm));
}

void ShadowMap::lit_counts(size_t n, const double* px, const double* py, const double* pz, const double* nx,
                           const double* ny, const double* nz, uint32_t* out) const {
  const LookupFrame F = frame_;  // a local copy: kept in registers
  const bool spot = light_.type == LightType::Spot;
  constexpr size_t kChunk = 64;
  double C[kChunk], Z[kChunk], X[kChunk], Y[kChunk], lim[kChunk];
  for (size_t i0 = 0; i0 < n; i0 += kChunk) {
    const size_t m = std::min(kChunk, n - i0);
    if (!spot) {
      for (size_t i = 0; i < m; ++i) {
        prepare<false>(F, light_, px[i0 + i], py[i0 + i], pz[i0 + i], nx[i0 + i], ny[i0 + i], nz[i0 + i], &C[i], &Z[i],
                       &X[i], &Y[i], &lim[i]);
        lim[i] = C[i] > 0 ? lim[i] : NAN;  // a face turned from the light: no test passes
      }
      counts_at(m, X, Y, lim, out + i0);
      continue;
    }
    for (size_t i = 0; i < m; ++i)
      prepare<true>(F, light_, px[i0 + i], py[i0 + i], pz[i0 + i], nx[i0 + i], ny[i0 + i], nz[i0 + i], &C[i], &Z[i],
                    &X[i], &Y[i], &lim[i]);
    for (size_t i = 0; i < m; ++i) lim[i] = C[i] > 0 ? lim[i] : NAN;  // turned from the light: none pass
    uint32_t cls[kChunk];
    block_classes(m, X, Y, lim, cls);
    for (size_t i = 0; i < m; ++i) {
      uint32_t r = cls[i];
      if (r != 0 && !(Z[i] > 0 && in_light_cone(light_, {px[i0 + i], py[i0 + i], pz[i0 + i]}))) r = 0;
      out[i0 + i] = r == kOpenClass ? count(X[i], Y[i], lim[i]) : r;
    }
  }
}

// The blocks decide most points: all pass (levels), all fail (0), or read
// the map (kOpenClass). The block of the kernel's first (clamped) texel
// bounds the whole kernel: the blocks were widened by one (8 texels) when it
// reaches beyond it. A NaN limit passes nothing.
void ShadowMap::block_classes(size_t m, const double* __restrict X, const double* __restrict Y,
                              const double* __restrict lim, uint32_t* __restrict cls) const {
  const Kernel k = kernel_of(s_.pcf);
  // floor(X + 0.5) for odd kernels; floor(X + 0) = floor(X) (−0 → +0 converts to the same int).
  const double half = k.odd ? 0.5 : 0.0;
  const int Dm = int(size_) - 1, nb = int(blocks_.blocks);
  const float *bmin = blocks_.min.data(), *bmax = blocks_.max.data();
  const uint32_t levels = levels_;
  for (size_t i = 0; i < m; ++i) {
    const bool ok = (X[i] == X[i]) & (Y[i] == Y[i]);
    double xs = X[i] == X[i] ? X[i] : 0.0, ys = Y[i] == Y[i] ? Y[i] : 0.0;  // no NaN into the int conversion
    int bx = int(std::floor(xs + half)) + k.first, by = int(std::floor(ys + half)) + k.first;
    bx = bx < 0 ? 0 : (bx > Dm ? Dm : bx);
    by = by < 0 ? 0 : (by > Dm ? Dm : by);
    const int blk = (by >> kDepthBlockShift) * nb + (bx >> kDepthBlockShift);
    const double lo = bmin[blk], hi = bmax[blk];
    uint32_t r = lim[i] <= hi ? kOpenClass : 0u;
    r = lim[i] <= lo ? levels : r;
    cls[i] = ok ? r : 0u;
  }
}

AffineLookup ShadowMap::affine_lookup() const {
  // prepare<false>: X = ox + sx·(p − e)·r, Y = oy − sy·(p − e)·u, z = (p − e)·f.
  const LookupFrame& F = frame_;
  const glm::dvec3 e(F.ex, F.ey, F.ez), r(F.rx, F.ry, F.rz), u(F.ux, F.uy, F.uz), f(F.fx, F.fy, F.fz);
  AffineLookup A;
  A.x = F.sx * r, A.x0 = F.ox - F.sx * glm::dot(e, r);
  A.y = -F.sy * u, A.y0 = F.oy + F.sy * glm::dot(e, u);
  A.z = f, A.z0 = -glm::dot(e, f);
  return A;
}

double ShadowMap::face_bias(double c) const {
  if (!(c > 0)) return NAN;
  return bias_of<false>(frame_, 0.0, c);  // the |d| term is the caller's (shadow_map.h)
}

namespace {
// Scalar loads beat the vector gathers here (two dependent gathers per point).
#if defined(__clang__)
#define ZS_SCALAR_LOOP _Pragma("clang loop vectorize(disable)")
#define ZS_NO_VECTORIZE
#else
#define ZS_SCALAR_LOOP
#define ZS_NO_VECTORIZE __attribute__((optimize("no-tree-vectorize")))
#endif
ZS_NO_VECTORIZE void read_one(const TiledDepths::Reader& md, size_t m, const uint32_t* tile, const uint32_t* off,
                              const double* lim, uint32_t* out) {
  ZS_SCALAR_LOOP
  for (size_t i = 0; i < m; ++i) out[i] = lim[i] <= double(md.at(tile[i], off[i])) ? 1u : 0u;
}
}  // namespace

bool ShadowMap::passes_all(double x0, double x1, double y0, double y1) const {
  if (!(std::isfinite(x0) && std::isfinite(x1) && std::isfinite(y0) && std::isfinite(y1)) || x1 < x0 || y1 < y0)
    return false;
  // The texels counts_at's kernels read for the corners (clamps and floor
  // are monotone, so every X and Y between read between them).
  const Kernel k = kernel_of(s_.pcf);
  const double half = k.odd ? 0.5 : 0.0, D8 = frame_.D + 8.0;
  const int Dm = int(size_) - 1;
  auto texel = [&](double v, int extra) {
    v = v < -8.0 ? -8.0 : (D8 < v ? D8 : v);
    const int t = int(std::floor(v + half)) + k.first + extra;
    return uint32_t(t < 0 ? 0 : (t > Dm ? Dm : t));
  };
  const uint32_t tx0 = texel(x0, 0) >> kMapTileShift, tx1 = texel(x1, k.width - 1) >> kMapTileShift;
  const uint32_t ty0 = texel(y0, 0) >> kMapTileShift, ty1 = texel(y1, k.width - 1) >> kMapTileShift;
  for (uint32_t ty = ty0; ty <= ty1; ++ty)
    for (uint32_t tx = tx0; tx <= tx1; ++tx)
      if (md_.stored(tx, ty)) return false;
  return true;
}

void ShadowMap::counts_at(size_t n, const double* X, const double* Y, const double* lim, uint32_t* out) const {
  const double D8 = frame_.D + 8.0;
  constexpr size_t kChunk = 64;
  double Xc[kChunk], Yc[kChunk], Lc[kChunk];  // local copies: the loops below vectorize
  uint32_t cls[kChunk];
  const int Dm = int(size_) - 1;
  for (size_t i0 = 0; i0 < n; i0 += kChunk) {
    const size_t m = std::min(kChunk, n - i0);
    const double *x = X + i0, *y = Y + i0, *l = lim + i0;
    // Clamped before the int conversion (a point far off the map reads its edge).
    for (size_t i = 0; i < m; ++i) {
      Xc[i] = x[i] < -8.0 ? -8.0 : (D8 < x[i] ? D8 : x[i]);  // std::clamp's order: NaN stays
      Yc[i] = y[i] < -8.0 ? -8.0 : (D8 < y[i] ? D8 : y[i]);
      Lc[i] = l[i];
    }
    if (levels_ == 1) {
      // 1-SM, PCF 1 (the defaults): one texel per point, read directly (a
      // block's range would cost a read of its own), in a loop without
      // calls or inner loops (count's arithmetic). A NaN limit passes no test.
      const TiledDepths::Reader md = md_.reader();
      uint32_t one[kChunk];
      uint32_t tile[kChunk], off[kChunk];  // vectorized: the texel's tile and place in it
      for (size_t i = 0; i < m; ++i) {
        const bool ok = (Xc[i] == Xc[i]) & (Yc[i] == Yc[i]);
        const double xs = ok ? Xc[i] : 0.0, ys = ok ? Yc[i] : 0.0;
        int tx = int(std::floor(xs + 0.5)), ty = int(std::floor(ys + 0.5));
        tx = tx < 0 ? 0 : (tx > Dm ? Dm : tx);
        ty = ty < 0 ? 0 : (ty > Dm ? Dm : ty);
        tile[i] = md.tile_of(uint32_t(tx), uint32_t(ty));
        off[i] = uint32_t(TiledDepths::index(0, uint32_t(tx), uint32_t(ty)));
        Lc[i] = ok ? Lc[i] : NAN;
      }
      read_one(md, m, tile, off, Lc, one);
      std::copy(one, one + m, out + i0);
      continue;
    }
    block_classes(m, Xc, Yc, Lc, cls);
    for (size_t i = 0; i < m; ++i) out[i0 + i] = cls[i] == kOpenClass ? count(Xc[i], Yc[i], Lc[i]) : cls[i];
  }
}

}  // namespace zs
