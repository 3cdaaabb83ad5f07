#include "shadows/sphere_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raster/tile_loop.h"
#include "shadows/depth_blocks.h"
#include "shadows/tiled_depths.h"

namespace zs {

ShadowMap build_sphere_map(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii,
                           const glm::dvec3& omega, uint32_t D, SphereDepth mode, const ShadowSettings& s,
                           int threads, SphereMapStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  Light light;
  light.type = LightType::Directional;
  light.direction = -omega;
  // The set's box, grown by the radii: the map covers every sphere whole.
  Bounds box;
  for (size_t i = 0; i < centres.size(); ++i) {
    const glm::dvec3 lo = centres[i] - glm::dvec3(radii[i]), hi = centres[i] + glm::dvec3(radii[i]);
    if (!(radii[i] > 0) || !std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z)) continue;  // not drawn
    box.lo = box.empty ? lo : glm::min(box.lo, lo);
    box.hi = box.empty ? hi : glm::max(box.hi, hi);
    box.empty = false;
  }
  LightFit fit = start_fit(light);
  for (int c = 0; c < 8 && !box.empty; ++c)
    fit.add({c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z});
  double z_near = 0;
  const Camera frame = shadow_map_frame(light, fit, box, D, &z_near);
  const View view(frame, D, D);
  const double texel = frame.height / D;  // world size of a texel

  // Each sphere's screen disc, binned to the map's tiles by its texel square.
  struct Disc {
    double x, y, z, r;  // centre in texels, depth, radius in texels
  };
  std::vector<Disc> discs(centres.size());
  const TileGrid grid{D, D, kMapTile, 1};
  std::vector<uint32_t> count(grid.count() + 1, 0);
  auto tiles_of = [&](const Disc& d, auto&& fn) {
    const int x0 = std::max(0, int(std::ceil(d.x - d.r))), x1 = std::min(int(D) - 1, int(std::floor(d.x + d.r)));
    const int y0 = std::max(0, int(std::ceil(d.y - d.r))), y1 = std::min(int(D) - 1, int(std::floor(d.y + d.r)));
    if (x0 > x1 || y0 > y1) return;
    for (int ty = y0 >> kMapTileShift; ty <= (y1 >> kMapTileShift); ++ty)
      for (int tx = x0 >> kMapTileShift; tx <= (x1 >> kMapTileShift); ++tx) fn(uint32_t(ty) * grid.cols() + tx);
  };
  for (size_t i = 0; i < centres.size(); ++i) {
    const ViewPoint v = view.project(centres[i]);
    discs[i] = {v.x, v.y, v.z, radii[i] / texel};
    if (!(std::isfinite(v.x) && std::isfinite(v.y) && discs[i].r > 0)) discs[i].r = -1;  // not drawn
    tiles_of(discs[i], [&](uint32_t t) { ++count[t + 1]; });
  }
  for (size_t t = 0; t < grid.count(); ++t) count[t + 1] += count[t];
  std::vector<uint32_t> ids(count.back()), fill(count.begin(), count.end() - 1);
  for (uint32_t i = 0; i < discs.size(); ++i) tiles_of(discs[i], [&](uint32_t t) { ids[fill[t]++] = i; });

  TiledDepths centre;
  centre.reset(D, 1);
  DepthBlocks blocks;
  blocks.reset(D);
  std::vector<uint32_t> busy;
  for (uint32_t t = 0; t < grid.count(); ++t)
    if (count[t + 1] != count[t]) {
      busy.push_back(t);
      centre.add_tile(t % grid.cols(), t / grid.cols());
    }
  struct Work {
    std::vector<double> db;
    std::vector<float> out;
    uint64_t written = 0;
  };
  tbb::enumerable_thread_specific<Work> work;
  TiledDepthsSink sink(centre);
  run_tiles(grid, busy, threads, sink, [&](uint32_t t, const TileRect& r) -> const float* {
    Work& w = work.local();
    const uint32_t W = r.width();
    w.db.assign(size_t(W) * r.height(), INFINITY);
    for (uint32_t k = count[t]; k < count[t + 1]; ++k) {
      const Disc& d = discs[ids[k]];
      const int x0 = std::max(int(r.x0), int(std::ceil(d.x - d.r)));
      const int x1 = std::min(int(r.x1) - 1, int(std::floor(d.x + d.r)));
      const int y0 = std::max(int(r.y0), int(std::ceil(d.y - d.r)));
      const int y1 = std::min(int(r.y1) - 1, int(std::floor(d.y + d.r)));
      const double r2 = d.r * d.r, rw = d.r * texel;
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double dx = x - d.x, dy = y - d.y, q = dx * dx + dy * dy;
          if (!(q <= r2)) continue;  // texel centre outside the disc
          // Impostor: the front surface, r·√(1 − ρ²/r²) nearer than the centre.
          const double z = mode == SphereDepth::CentreDisc ? d.z : d.z - rw * std::sqrt(std::max(0.0, 1 - q / r2));
          double& o = w.db[size_t(y - r.y0) * W + size_t(x - r.x0)];
          o = std::min(o, z + 0.0);
          ++w.written;
        }
    }
    w.out.resize(w.db.size());
    round_depths_up(w.db.data(), w.db.size(), w.out.data());
    fold_block_ranges(w.out.data(), W, r.x0, r.y0, r.x1, r.y1, blocks);  // whole blocks per tile
    return w.out.data();
  });
  if (stats) {
    stats->texels_written = 0;
    for (const Work& w : work) stats->texels_written += w.written;
    stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  return ShadowMap::from_tiles(light, frame, std::move(centre), s, std::move(blocks));
}

SphereAoMaps build_sphere_ao_maps(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii,
                                  const std::vector<glm::dvec3>& dirs, uint32_t size, SphereDepth mode,
                                  const ShadowSettings& s, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  SphereAoMaps out;
  out.dirs = dirs;
  out.maps.resize(dirs.size());
  threads = std::max(1, threads);
  if (int(dirs.size()) >= threads && threads > 1) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      tbb::parallel_for(size_t(0), dirs.size(), [&](size_t k) {
        out.maps[k] = build_sphere_map(centres, radii, dirs[k], size, mode, s, 1);
      });
    });
  } else {
    for (size_t k = 0; k < dirs.size(); ++k) out.maps[k] = build_sphere_map(centres, radii, dirs[k], size, mode, s, threads);
  }
  for (const ShadowMap& m : out.maps) out.bytes += m.bytes();
  out.ms_build = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

double ambient_occlusion(const std::vector<ShadowMap>& maps, const std::vector<glm::dvec3>& dirs, const glm::dvec3& p,
                         const glm::dvec3& n) {
  double num = 0, den = 0;
  for (size_t k = 0; k < dirs.size(); ++k) {
    const double w = glm::dot(n, dirs[k]);
    if (!(w > 0)) continue;
    den += w;
    num += w * maps[k].lit(p, n);
  }
  return den > 0 ? num / den : 1.0;
}

}  // namespace zs
