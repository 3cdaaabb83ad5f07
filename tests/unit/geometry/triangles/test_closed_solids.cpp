// In geometry/triangles/: beside closed_solid_sides; the maps only show what it leaves out.
// closed_solid_sides on closed, open, flipped and non-manifold meshes, and
// the directional maps it lets leave out the solids' far faces: depths
// unchanged, texel for texel.
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lighting/shadow_map.h"
#include "geometry/triangles/closed_solids.h"

namespace zs {
namespace {

// A closed, outward-wound, star-shaped (so not convex) blob: an octahedron
// subdivided `levels` times, its points pushed to random radii.
TriangleMesh blob(uint32_t seed, const glm::dvec3& centre, double size, int levels = 3) {
  TriangleMesh m;
  m.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.tris = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.points.push_back(glm::normalize(m.points[a] + m.points[b]));
      return mid[key] = uint32_t(m.points.size() - 1);
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& t : m.tris) {
      const uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca}), next.push_back({ab, t[1], bc}), next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    m.tris = next;
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.55, 1.0);
  for (glm::dvec3& p : m.points) p = centre + size * U(rng) * p;
  m.surface.assign(m.tris.size(), 0);
  return m;
}

std::vector<int8_t> all(size_t n, int8_t v) { return std::vector<int8_t>(n, v); }

TEST(ClosedSolids, SidesOfClosedOpenFlippedAndNonManifold) {
  const TriangleMesh b = blob(1, {0.3, -0.2, 0.1}, 1.0);
  ASSERT_EQ(b.tris.size(), 512u);
  EXPECT_EQ(closed_solid_sides(b), all(b.tris.size(), 1));
  TriangleMesh flipped = b;  // wound inwards
  for (auto& t : flipped.tris) std::swap(t[1], t[2]);
  EXPECT_EQ(closed_solid_sides(flipped), all(b.tris.size(), -1));
  TriangleMesh open = b;  // a hole
  open.tris.pop_back();
  EXPECT_EQ(closed_solid_sides(open), all(open.tris.size(), 0));
  TriangleMesh one_flipped = b;  // closed but not consistently oriented
  std::swap(one_flipped.tris[7][1], one_flipped.tris[7][2]);
  EXPECT_EQ(closed_solid_sides(one_flipped), all(b.tris.size(), 0));
  TriangleMesh doubled = b;  // a face twice: its edges have three uses
  doubled.tris.push_back(b.tris[0]);
  EXPECT_EQ(closed_solid_sides(doubled), all(doubled.tris.size(), 0));
  // Two components: the closed blob keeps its side, an open quad gets 0; far
  // from the origin the volume's sign still comes out right.
  TriangleMesh two = blob(2, {1e6, -2e6, 5e5}, 0.01);
  const size_t n = two.tris.size();
  const uint32_t q = uint32_t(two.points.size());
  two.points.insert(two.points.end(), {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  two.tris.push_back({q, q + 1, q + 2}), two.tris.push_back({q, q + 2, q + 3});
  const std::vector<int8_t> s = closed_solid_sides(two);
  EXPECT_EQ(std::vector<int8_t>(s.begin(), s.begin() + long(n)), all(n, 1));
  EXPECT_EQ(s[n], 0);
  EXPECT_EQ(s[n + 1], 0);
}

TEST(ClosedSolids, DirectionalMapsWithoutTheFarFacesAreTheSame) {
  // Three blobs (one wound inwards): the map with the solids' far faces left
  // out holds the same depth at every texel. (No ground: with caster culling
  // off it would enter the map too.)
  TriangleMesh m = blob(3, {0, 0.9, 0}, 0.8);
  for (const auto& [seed, c, flip] : {std::tuple{4u, glm::dvec3(1.4, 0.6, 0.3), false},
                                      std::tuple{5u, glm::dvec3(-1.0, 0.7, -0.8), true}}) {
    TriangleMesh o = blob(seed, c, 0.6);
    if (flip)
      for (auto& t : o.tris) std::swap(t[1], t[2]);
    const uint32_t base = uint32_t(m.points.size());
    m.points.insert(m.points.end(), o.points.begin(), o.points.end());
    for (auto t : o.tris) m.tris.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  m.surface.assign(m.tris.size(), 0);
  m.solid = closed_solid_sides(m);
  const Bounds scene = triangle_bounds(m);
  for (const glm::dvec3 dir : {glm::dvec3(-1, -2, -1), glm::dvec3(0.3, -1, 0.1), glm::dvec3(1, -0.4, -0.2)}) {
    Light light;
    light.type = LightType::Directional;
    light.direction = dir;
    ShadowSettings s;
    s.map_size = 256;
    ShadowMapStats culled, kept;
    const ShadowMap a = ShadowMap::build(m, light, start_fit(light), scene, s, 1, &culled);
    s.cull_casters = false;
    const ShadowMap b = ShadowMap::build(m, light, start_fit(light), scene, s, 1, &kept);
    EXPECT_GT(culled.casters_back_faces, 600u);  // about half of the blobs' 1536 faces
    EXPECT_EQ(kept.casters_back_faces, 0u);
    EXPECT_LT(culled.caster_fragments, kept.caster_fragments * 3 / 4);
    uint64_t covered = 0, differ = 0;
    for (uint32_t y = 0; y < 256; ++y)
      for (uint32_t x = 0; x < 256; ++x) {
        covered += b.depth(x, y) < INFINITY;
        differ += a.depth(x, y) != b.depth(x, y);
      }
    EXPECT_GT(covered, 5000u);
    EXPECT_EQ(differ, 0u);
  }
}

}  // namespace
}  // namespace zs
