// Ambient occlusion from orthographic sphere maps (shadows/sphere_map.h): an
// isolated sphere is unoccluded, a sphere inside a closed shell is dark, the
// maps converge to exact visibility as they grow, and threads change nothing.
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "shadows/ao_directions.h"
#include "shadows/sphere_map.h"

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

std::vector<ShadowMap> maps_for(const Set& set, const std::vector<glm::dvec3>& dirs, uint32_t size, SphereDepth mode,
                                const ShadowSettings& s, int threads = 2) {
  std::vector<ShadowMap> m;
  for (const glm::dvec3& d : dirs) m.push_back(build_sphere_map(set.c, set.r, d, size, mode, s, threads));
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
    for (const glm::dvec3& n : spiral(2000)) lo = std::min(lo, ambient_occlusion(maps, dirs, one.c[0] + 0.7 * n, n));
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
  for (const glm::dvec3& n : spiral(500)) hi = std::max(hi, ambient_occlusion(maps, dirs, n, n));
  EXPECT_LE(hi, 0.05);
  // The shell's own outside is lit from outside.
  double outer = 0;
  for (const glm::dvec3& d : spiral(50)) outer += ambient_occlusion(maps, dirs, 3.6 * d, d) / 50;
  EXPECT_GT(outer, 0.5);
}

// Exact visibility: the ray from p towards w meets another sphere.
bool blocked(const Set& s, size_t own, const glm::dvec3& p, const glm::dvec3& w) {
  for (size_t j = 0; j < s.c.size(); ++j) {
    if (j == own) continue;
    const glm::dvec3 oc = p - s.c[j];
    const double b = glm::dot(oc, w), c = glm::dot(oc, oc) - s.r[j] * s.r[j];
    const double disc = b * b - c;
    if (disc >= 0 && -b + std::sqrt(disc) > 0) return true;
  }
  return false;
}

TEST(SphereAo, MapsConvergeToExactVisibilityAndThreadsChangeNothing) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(0, 1);
  Set set;
  while (set.c.size() < 40) {  // non-overlapping, at least 0.05 apart
    const glm::dvec3 c(3 * U(rng), 3 * U(rng), 3 * U(rng));
    const double r = 0.2 + 0.3 * U(rng);
    bool ok = true;
    for (size_t j = 0; j < set.c.size() && ok; ++j) ok = glm::length(c - set.c[j]) > r + set.r[j] + 0.05;
    if (ok) set.c.push_back(c), set.r.push_back(r);
  }
  const std::vector<glm::dvec3> dirs = ao_directions(18);
  const std::vector<glm::dvec3> sp = spiral(60);
  std::vector<double> exact;
  for (size_t i = 0; i < set.c.size(); ++i)
    for (const glm::dvec3& n : sp) {
      const glm::dvec3 p = set.c[i] + set.r[i] * n;
      double num = 0, den = 0;
      for (const glm::dvec3& w : dirs) {
        const double k = glm::dot(n, w);
        if (!(k > 0)) continue;
        den += k;
        num += blocked(set, i, p, w) ? 0 : k;
      }
      exact.push_back(den > 0 ? num / den : 1);
    }
  std::vector<double> err;
  for (uint32_t size : {64u, 256u, 1024u}) {
    const auto maps = maps_for(set, dirs, size, SphereDepth::CentreDisc, ao_settings(1e-4, 0));
    double sum = 0;
    size_t q = 0;
    for (size_t i = 0; i < set.c.size(); ++i)
      for (const glm::dvec3& n : sp) sum += std::abs(ambient_occlusion(maps, dirs, set.c[i] + set.r[i] * n, n) - exact[q++]);
    err.push_back(sum / double(q));
  }
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
  EXPECT_LT(err[2], 0.01);
  // One thread or several: the same lit counts everywhere.
  const auto one = maps_for(set, dirs, 256, SphereDepth::Impostor, ao_settings(1e-4, 1.5), 1);
  const auto three = maps_for(set, dirs, 256, SphereDepth::Impostor, ao_settings(1e-4, 1.5), 3);
  for (size_t k = 0; k < dirs.size(); ++k)
    for (uint32_t y = 0; y < 256; ++y)
      for (uint32_t x = 0; x < 256; ++x) ASSERT_EQ(one[k].depth(x, y), three[k].depth(x, y));
}

}  // namespace
}  // namespace zs
