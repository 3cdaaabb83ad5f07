// Ambient occlusion from orthographic sphere maps (lighting/sphere_map.h): an
// isolated sphere is unoccluded, a sphere inside a closed shell is dark, the
// maps converge to exact visibility as they grow, and threads change nothing.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lighting/ao_directions.h"
#include "lighting/sphere_map.h"
#include "lighting/tiled_depths.h"
#include "lighting/transmittance_lists.h"

namespace zs {
namespace {

struct Set {
  std::vector<glm::dvec3> c;
  std::vector<double> r;
};

ShadowSettings ao_settings(double bias, double slope) {
  ShadowSettings s;
  s.bias = bias;
  s.slope_bias = slope;
  return s;
}

// One map per direction, each built on `threads` threads; with `alpha`,
// their translucent lists too.
SphereAoMaps maps_for(const Set& set, const std::vector<glm::dvec3>& dirs, uint32_t size, SphereDepth mode,
                      const ShadowSettings& s, int threads = 2, const std::vector<float>* alpha = nullptr) {
  SphereAoMaps m;
  m.dirs = dirs;
  if (alpha) m.translucent.resize(dirs.size());
  for (size_t k = 0; k < dirs.size(); ++k)
    m.maps.push_back(build_sphere_map(set.c, set.r, dirs[k], size, mode, s, threads, nullptr, alpha,
                                      alpha ? &m.translucent[k] : nullptr));
  return m;
}

// Points spread over a sphere's surface (golden spiral), with their normals.
std::vector<glm::dvec3> spiral(size_t n) {
  std::vector<glm::dvec3> p;
  for (size_t i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, rho = std::sqrt(1 - z * z), phi = 2.39996322972865332 * i;
    p.push_back({rho * std::cos(phi), rho * std::sin(phi), z});
  }
  return p;
}

TEST(SphereAo, IsolatedSphereIsUnoccluded) {
  const Set one{{{0.3, -0.2, 0.1}}, {0.7}};
  const std::vector<glm::dvec3> dirs = ao_directions(66);
  for (SphereDepth mode : {SphereDepth::CentreDisc, SphereDepth::Impostor}) {
    const auto maps = maps_for(one, dirs, 256, mode,
                               mode == SphereDepth::CentreDisc ? ao_settings(1e-4, 0) : ao_settings(1e-4, 1.5));
    double lo = 1;
    for (const glm::dvec3& n : spiral(2000)) lo = std::min(lo, ambient_occlusion(maps, one.c[0] + 0.7 * n, n));
    EXPECT_GE(lo, 0.99) << (mode == SphereDepth::CentreDisc ? "disc" : "impostor");
  }
}

TEST(SphereAo, SphereInsideAClosedShellIsDark) {
  Set set{{{0, 0, 0}}, {1.0}};
  for (const glm::dvec3& d : spiral(300)) {  // neighbours 0.6 apart, radius 0.6: overlapping
    set.c.push_back(3.0 * d);
    set.r.push_back(0.6);
  }
  const std::vector<glm::dvec3> dirs = ao_directions(66);
  const auto maps = maps_for(set, dirs, 512, SphereDepth::CentreDisc, ao_settings(1e-3, 0));
  double hi = 0;
  for (const glm::dvec3& n : spiral(500)) hi = std::max(hi, ambient_occlusion(maps, n, n));
  EXPECT_LE(hi, 0.05);
  // The shell's own outside is lit from outside.
  double outer = 0;
  for (const glm::dvec3& d : spiral(50)) outer += ambient_occlusion(maps, 3.6 * d, d) / 50;
  EXPECT_GT(outer, 0.5);
}

// Exact transmittance with alpha occluders: Π(1 − α) over the spheres the ray meets.
double passed(const Set& s, const std::vector<float>& alpha, size_t own, const glm::dvec3& p, const glm::dvec3& w) {
  double t = 1;
  for (size_t j = 0; j < s.c.size(); ++j) {
    if (j == own) continue;
    const glm::dvec3 oc = p - s.c[j];
    const double b = glm::dot(oc, w), c = glm::dot(oc, oc) - s.r[j] * s.r[j];
    const double disc = b * b - c;
    if (disc >= 0 && -b + std::sqrt(disc) > 0) t *= alpha[j] >= 1.f ? 0.0 : alpha[j] > 0.f ? 1.0 - alpha[j] : 1.0;
  }
  return t;
}

// Forty spheres in a 3³ box, none overlapping (at least 0.05 apart).
Set scattered(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  Set set;
  while (set.c.size() < 40) {
    const glm::dvec3 c(3 * U(rng), 3 * U(rng), 3 * U(rng));
    const double r = 0.2 + 0.3 * U(rng);
    bool ok = true;
    for (size_t j = 0; j < set.c.size() && ok; ++j) ok = glm::length(c - set.c[j]) > r + set.r[j] + 0.05;
    if (ok) set.c.push_back(c), set.r.push_back(r);
  }
  return set;
}

// Exact AO at sp's points on every sphere of the set (alpha occluders;
// all alpha 1: exact visibility), point by point.
std::vector<double> exact_ao(const Set& set, const std::vector<float>& alpha, const std::vector<glm::dvec3>& dirs,
                             const std::vector<glm::dvec3>& sp) {
  std::vector<double> exact;
  for (size_t i = 0; i < set.c.size(); ++i)
    for (const glm::dvec3& n : sp) {
      double num = 0, den = 0;
      for (const glm::dvec3& w : dirs) {
        const double k = glm::dot(n, w);
        if (!(k > 0)) continue;
        den += k;
        num += k * passed(set, alpha, i, set.c[i] + set.r[i] * n, w);
      }
      exact.push_back(den > 0 ? num / den : 1);
    }
  return exact;
}

// The maps' mean |AO − exact| at those points for maps of 64², 256², 1024².
std::vector<double> map_errors(const Set& set, const std::vector<glm::dvec3>& dirs, const std::vector<glm::dvec3>& sp,
                               const std::vector<double>& exact, const std::vector<float>* alpha) {
  std::vector<double> err;
  for (uint32_t size : {64u, 256u, 1024u}) {
    const auto maps = maps_for(set, dirs, size, SphereDepth::CentreDisc, ao_settings(1e-4, 0), 2, alpha);
    double sum = 0;
    size_t q = 0;
    for (size_t i = 0; i < set.c.size(); ++i)
      for (const glm::dvec3& n : sp) sum += std::abs(ambient_occlusion(maps, set.c[i] + set.r[i] * n, n) - exact[q++]);
    err.push_back(sum / double(q));
  }
  return err;
}

TEST(SphereAo, MapsConvergeToExactVisibilityAndThreadsChangeNothing) {
  const Set set = scattered(9);
  const std::vector<glm::dvec3> dirs = ao_directions(18);
  const std::vector<glm::dvec3> sp = spiral(60);
  const std::vector<double> err =
      map_errors(set, dirs, sp, exact_ao(set, std::vector<float>(set.c.size(), 1.f), dirs, sp), nullptr);
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
  EXPECT_LT(err[2], 0.01);
  // One thread or several: the same lit counts everywhere.
  const auto one = maps_for(set, dirs, 256, SphereDepth::Impostor, ao_settings(1e-4, 1.5), 1);
  const auto three = maps_for(set, dirs, 256, SphereDepth::Impostor, ao_settings(1e-4, 1.5), 3);
  for (size_t k = 0; k < dirs.size(); ++k)
    for (uint32_t y = 0; y < 256; ++y)
      for (uint32_t x = 0; x < 256; ++x) ASSERT_EQ(one.maps[k].depth(x, y), three.maps[k].depth(x, y));
}

TEST(TransmittanceLists, ProductsOfTheDiscsInFrontOfTheLimit) {
  TransmittanceLists l;
  l.reset(100);  // 2×2 tiles
  std::vector<TranslucentTexel> d = {{5, 2, 3.0, 0.5}, {5, 1, 1.0, 0.25}, {5, 7, 3.0, 0.8}, {6, 0, 2.0, 0.1}};
  l.set_tile(1, 0, d);
  l.count_fragments();
  EXPECT_EQ(l.fragments(), 4u);
  const uint32_t x = 64 + 5, y = 0;
  EXPECT_EQ(l.transmittance(x, y, 1.0), 1.f);  // z < lim only: the disc at 1 is not in front of 1
  EXPECT_EQ(l.transmittance(x, y, 2.0), 0.25f);
  EXPECT_EQ(l.transmittance(x, y, 3.5), float(0.25 * 0.5 * 0.8));
  EXPECT_EQ(l.transmittance(64 + 6, 0, 2.5), 0.1f);
  EXPECT_EQ(l.transmittance(5, 0, 10.0), 1.f);   // another tile: no list
  EXPECT_EQ(l.transmittance(x, 1, 10.0), 1.f);   // another texel of the tile
}

TEST(SphereAo, AlphaOccludersConvergeToExactTransmittance) {
  const Set set = scattered(4);
  std::vector<float> alpha(set.c.size());
  for (size_t i = 0; i < alpha.size(); ++i) alpha[i] = i % 5 == 0 ? 1.f : i % 7 == 0 ? 0.f : 0.15f + 0.1f * (i % 6);
  const std::vector<glm::dvec3> dirs = ao_directions(18);
  const std::vector<glm::dvec3> sp = spiral(60);
  const std::vector<double> exact = exact_ao(set, alpha, dirs, sp);
  ASSERT_LT(*std::min_element(exact.begin(), exact.end()), 0.7);  // the scene does occlude
  const std::vector<double> err = map_errors(set, dirs, sp, exact, &alpha);
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
  EXPECT_LT(err[2], 0.01);
  // Every alpha 1: no list, and the opaque maps' AO bit for bit.
  const std::vector<float> ones(set.c.size(), 1.f);
  const auto a = maps_for(set, dirs, 128, SphereDepth::CentreDisc, ao_settings(1e-4, 0), 1, &ones);
  const auto o = maps_for(set, dirs, 128, SphereDepth::CentreDisc, ao_settings(1e-4, 0), 1);
  for (const TransmittanceLists& l : a.translucent) EXPECT_EQ(l.fragments(), 0u);
  for (size_t i = 0; i < set.c.size(); ++i)
    for (const glm::dvec3& n : sp)
      ASSERT_EQ(ambient_occlusion(a, set.c[i] + set.r[i] * n, n), ambient_occlusion(o, set.c[i] + set.r[i] * n, n));
}

// The centre-disc map texel by texel against the definition: the minimum,
// over the discs containing the texel centre, of the centre depth rounded up
// to a float. Large spheres cover whole 64-texel tiles (those start at the
// covering disc's depth instead of binning it), small ones do not.
TEST(SphereAo, CentreDiscMapIsTheMinimumOverDiscs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1), R(0.01, 0.08);
  Set set;
  for (int i = 0; i < 300; ++i) {
    set.c.push_back({U(rng), U(rng), U(rng)});
    set.r.push_back(i < 12 ? 0.35 + 0.1 * std::abs(U(rng)) : R(rng));  // a few cover several tiles
  }
  const uint32_t D = 512;
  for (int threads : {1, 2}) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.3, 1.0, -0.4));
    const ShadowMap m = build_sphere_map(set.c, set.r, dir, D, SphereDepth::CentreDisc, ao_settings(0, 0), threads);
    const View& v = m.view();
    std::vector<double> best(size_t(D) * D, INFINITY);
    std::vector<uint8_t> unsure(size_t(D) * D, 0);
    for (size_t i = 0; i < set.c.size(); ++i) {
      const ViewPoint p = v.project(set.c[i]);
      const double r = set.r[i] * v.scale_x();
      const int x0 = std::max(0, int(p.x - r) - 1), x1 = std::min(int(D) - 1, int(p.x + r) + 1);
      const int y0 = std::max(0, int(p.y - r) - 1), y1 = std::min(int(D) - 1, int(p.y + r) + 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double dx = x - p.x, dy = y - p.y, d2 = dx * dx + dy * dy;
          if (std::abs(d2 - r * r) <= 1e-9 * r * r) unsure[size_t(y) * D + x] = 1;  // on the rim
          if (d2 <= r * r) best[size_t(y) * D + x] = std::min(best[size_t(y) * D + x], p.z);
        }
    }
    uint64_t checked = 0, covered = 0;
    for (uint32_t y = 0; y < D; ++y)
      for (uint32_t x = 0; x < D; ++x) {
        if (unsure[size_t(y) * D + x]) continue;
        float want;
        round_depths_up(&best[size_t(y) * D + x], 1, &want);
        ASSERT_EQ(m.depth(x, y), want) << x << "," << y << " threads " << threads;
        ++checked;
        covered += want < INFINITY;
      }
    EXPECT_GT(checked, uint64_t(D) * D * 99 / 100);
    EXPECT_GT(covered, uint64_t(D) * D / 4);
  }
}

TEST(SphereAo, BatchesOfDirectionsAddTheSameSums) {
  const Set set = scattered(5);
  const std::vector<glm::dvec3> dirs = ao_directions(66);
  const auto all = maps_for(set, dirs, 128, SphereDepth::CentreDisc, ao_settings(1e-4, 0));
  std::vector<double> px, py, pz, nx, ny, nz;
  for (size_t i = 0; i < set.c.size(); ++i)
    for (const glm::dvec3& n : spiral(30)) {
      const glm::dvec3 p = set.c[i] + set.r[i] * n;
      px.push_back(p.x), py.push_back(p.y), pz.push_back(p.z), nx.push_back(n.x), ny.push_back(n.y), nz.push_back(n.z);
    }
  const size_t n = px.size();
  std::vector<double> num(n, 0), den(n, 0), bnum(n, 0), bden(n, 0);
  accumulate_ao(all, n, px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), num.data(), den.data());
  for (size_t k0 = 0; k0 < dirs.size(); k0 += 20) {  // batches of 20, 20, 20, 6
    SphereAoMaps b;
    for (size_t k = k0; k < std::min(dirs.size(), k0 + 20); ++k) b.dirs.push_back(dirs[k]), b.maps.push_back(all.maps[k]);
    accumulate_ao(b, n, px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), bnum.data(), bden.data());
  }
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(num[i], bnum[i]);
    ASSERT_EQ(den[i], bden[i]);
    // And the one-point form gives the same AO.
    ASSERT_EQ(ambient_occlusion(all, {px[i], py[i], pz[i]}, {nx[i], ny[i], nz[i]}), den[i] > 0 ? num[i] / den[i] : 1.0);
  }
}

}  // namespace
}  // namespace zs
