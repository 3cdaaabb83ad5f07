#include "render/spheres/sphere_ao.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lighting/ao_directions.h"
#include "lighting/tiled_depths.h"
#include "base/util/bytes_str.h"

namespace zs {

uint64_t sphere_ao_map_bytes_bound(const SphereRenderSettings& rs) {
  const uint64_t D = rs.ao.map_size, tiles = (D + kMapTile - 1) / kMapTile, blocks = (D + 7) / 8;
  return D * D * 4 + blocks * blocks * 8 + tiles * tiles * 4;  // every tile stored, its block ranges, its slots
}

uint64_t sphere_ao_bytes_bound(const SphereRenderSettings& rs) {
  return uint64_t(rs.ao.directions) * sphere_ao_map_bytes_bound(rs);
}

uint64_t sphere_ao_sums_bytes(const SphereRenderSettings& rs) {
  return uint64_t(rs.width) * rs.height * sizeof(double);
}

uint32_t sphere_ao_batch_size(const SphereRenderSettings& rs, uint64_t budget, uint64_t held, int threads) {
  const std::string need = std::to_string(rs.ao.directions) + " AO maps of " + std::to_string(rs.ao.map_size) +
                           "² (up to " + bytes_str(sphere_ao_bytes_bound(rs)) + ")";
  if (rs.mode != SphereMode::Opaque)
    throw std::runtime_error(std::string("ao in render.mode \"") + to_string(rs.mode) +
                             "\" needs every AO map in memory, and the budget of " + bytes_str(budget) +
                             " cannot hold " + need + "; raise --memory-budget or lower ao.map_size or ao.directions");
  const uint64_t sums = sphere_ao_sums_bytes(rs), per_map = sphere_ao_map_bytes_bound(rs);
  if (held + sums + per_map > budget)
    throw std::runtime_error("memory budget of " + bytes_str(budget) + " cannot hold even one of " + need +
                             " with the image's AO sums (" + bytes_str(sums) +
                             "); raise --memory-budget or lower ao.map_size");
  uint32_t batch = uint32_t(std::min<uint64_t>(rs.ao.directions, (budget - held - sums) / per_map));
  if (rs.ao.alpha_occluders) batch = std::min<uint32_t>(batch, uint32_t(std::max(1, threads)));
  return batch;
}

SphereAoMaps build_sphere_ao(const SphereSet& s, const std::vector<glm::vec4>& colors, const SphereRenderSettings& rs,
                             const std::vector<glm::dvec3>& dirs) {
  // Default bias: 1 % of the smallest radius (discs cannot shadow their own
  // sphere; the bias only absorbs rounding). Impostor depth needs the slope bias.
  double rmin = INFINITY;
  for (double r : s.radii)
    if (r > 0 && std::isfinite(r)) rmin = std::min(rmin, r);
  ShadowSettings ss;
  ss.map_size = rs.ao.map_size;
  ss.bias = rs.ao.bias >= 0 ? rs.ao.bias : (std::isfinite(rmin) ? 0.01 * rmin : 0.0);
  ss.slope_bias = rs.ao.impostor_depth ? 1.5 : 0.0;
  std::vector<float> alpha;
  if (rs.ao.alpha_occluders) {
    alpha.resize(colors.size());
    for (size_t i = 0; i < colors.size(); ++i) alpha[i] = colors[i].a;
  }
  return build_sphere_ao_maps(s.centres, s.radii, dirs, rs.ao.map_size,
                              rs.ao.impostor_depth ? SphereDepth::Impostor : SphereDepth::CentreDisc, ss,
                              std::max(1, rs.threads), rs.ao.alpha_occluders ? &alpha : nullptr);
}

std::shared_ptr<const SphereAoMaps> sphere_ao_maps(const SphereSet& s, const std::vector<glm::vec4>& colors,
                                                   const SphereRenderSettings& rs, uint64_t available) {
  if (sphere_ao_bytes_bound(rs) > available) return nullptr;
  auto maps = std::make_shared<const SphereAoMaps>(build_sphere_ao(s, colors, rs, ao_directions(rs.ao.directions)));
  if (maps->bytes > available) return nullptr;  // alpha occluders' lists: known only once built
  return maps;
}

void AoPoints::clear() {
  pixel.clear();
  for (std::vector<double>* v : {&px, &py, &pz, &nx, &ny, &nz, &num, &den}) v->clear();
}

void AoPoints::add(size_t image_pixel, const glm::dvec3& p, const glm::dvec3& n) {
  pixel.push_back(image_pixel);
  px.push_back(p.x), py.push_back(p.y), pz.push_back(p.z);
  nx.push_back(n.x), ny.push_back(n.y), nz.push_back(n.z);
}

void ao_sums(AoPoints& pts, const SphereAoMaps* held, const std::vector<glm::dvec3>& dirs,
             const std::vector<double>& image_sums) {
  const size_t n = pts.size();
  pts.num.assign(n, 0.0);
  pts.den.assign(n, 0.0);
  if (held) {
    accumulate_ao(*held, n, pts.px.data(), pts.py.data(), pts.pz.data(), pts.nx.data(), pts.ny.data(), pts.nz.data(),
                  pts.num.data(), pts.den.data());
    return;
  }
  for (size_t i = 0; i < n; ++i) pts.num[i] = image_sums[pts.pixel[i]];
  ao_weights(dirs, n, pts.nx.data(), pts.ny.data(), pts.nz.data(), pts.den.data());
}

void add_ao_batch(AoPoints& pts, const SphereAoMaps& batch, std::vector<double>& image_sums) {
  const size_t n = pts.size();
  pts.num.resize(n);
  pts.den.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) pts.num[i] = image_sums[pts.pixel[i]];  // carried on, in direction order
  accumulate_ao(batch, n, pts.px.data(), pts.py.data(), pts.pz.data(), pts.nx.data(), pts.ny.data(), pts.nz.data(),
                pts.num.data(), pts.den.data());
  for (size_t i = 0; i < n; ++i) image_sums[pts.pixel[i]] = pts.num[i];
}

}  // namespace zs
