// clip_triangles: a closed cube cut by planes keeps exactly the area the
// planes keep, every kept point inside them, and stays watertight (every cut
// edge shared by two triangles uses one point).
#include <cmath>
#include <map>
#include <utility>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "geometry/triangles/clip_triangles.h"

namespace zs {
namespace {

// The unit cube [0, 1]³ as 12 outward triangles.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.points.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  m.tris = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
            {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  m.surface.assign(m.tris.size(), 3);
  return m;
}

double area(const TriangleMesh& m) {
  double a = 0;
  for (size_t t = 0; t < m.tris.size(); ++t) a += 0.5 * glm::length(face_normal(m, t));
  return a;
}

TEST(ClipTriangles, KeepsTheAreaThePlanesKeep) {
  TriangleMesh m = cube();
  ClipRegion r;
  r.planes.push_back({glm::dvec3(1, 0, 0), -0.5});  // x <= 0.5
  const TriangleClipCounts c = clip_triangles(m, r);
  EXPECT_NEAR(area(m), 1 + 4 * 0.5, 1e-12);  // the x = 0 face and half of four sides
  EXPECT_EQ(c.dropped, 2u);                  // the x = 1 face
  EXPECT_GT(c.cut, 0u);
  for (const auto& t : m.tris)
    for (uint32_t v : t) EXPECT_LE(m.points[v].x, 0.5);
  for (uint32_t s : m.surface) EXPECT_EQ(s, 3u);
  // Watertight apart from the cut: each edge off the plane x = 0.5 is used twice.
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  for (const auto& [e, n] : uses) {
    const bool on_cut = m.points[e.first].x == 0.5 && m.points[e.second].x == 0.5;
    EXPECT_EQ(n, on_cut ? 1 : 2) << e.first << "-" << e.second;
  }
  // An oblique plane and a box together: the area the region keeps.
  TriangleMesh b = cube();
  ClipRegion box;
  box.add_box({-1, -1, 0.25}, {2, 2, 0.75});  // z in [0.25, 0.75]: half of four sides
  clip_triangles(b, box);
  EXPECT_NEAR(area(b), 4 * 0.5, 1e-12);
}

TEST(ClipTriangles, NothingToCut) {
  TriangleMesh m = cube();
  ClipRegion keep_all;
  keep_all.planes.push_back({glm::dvec3(0, 1, 0), -5.0});
  EXPECT_EQ(clip_triangles(m, keep_all).cut, 0u);
  EXPECT_EQ(m.tris, cube().tris);
  ClipRegion none;
  none.planes.push_back({glm::dvec3(0, 1, 0), 5.0});
  EXPECT_EQ(clip_triangles(m, none).dropped, 12u);
  EXPECT_TRUE(m.tris.empty());
}

}  // namespace
}  // namespace zs
