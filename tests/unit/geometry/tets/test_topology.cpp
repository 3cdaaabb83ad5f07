#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "geometry/tets/default_mesh.h"
#include "geometry/tets/hex_split.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"

namespace zs {
namespace {

// A structured grid of n^3 unit cubes, 5 tets each.
TetMesh grid(uint32_t n, double scale = 1.0, glm::dvec3 offset = {0, 0, 0}) {
  TetMesh m;
  const uint32_t nn = n + 1;
  for (uint32_t k = 0; k < nn; ++k)
    for (uint32_t j = 0; j < nn; ++j)
      for (uint32_t i = 0; i < nn; ++i) m.points.push_back(offset + scale * glm::dvec3(i, j, k));
  m.scalars.assign(m.points.size(), 1.0);
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i) append_hex_5tets(grid_hex(i, j, k, nn, nn), (i + j + k) & 1, m.tets);
  return m;
}

// How many faces have vertex v.
size_t faces_on(const Topology& t, uint32_t v) {
  size_t n = 0;
  for (uint32_t f = 0; f < t.num_faces(); ++f) {
    const auto fv = t.face(f);
    n += fv[0] == v || fv[1] == v || fv[2] == v;
  }
  return n;
}

TEST(Topology, TwoTetsSharingAFace) {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  const Topology t = build_topology(m);
  EXPECT_EQ(t.num_faces(), 7u);
  EXPECT_EQ(t.num_boundary_faces, 6u);
  // The shared face (0,1,2) knows both tets; each tet knows it.
  const auto tf = build_tet_faces(m, t);
  const uint32_t shared = tf[0][3];
  EXPECT_EQ(t.face(shared), (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(tf[1][3], shared);
  EXPECT_EQ(t.tet0(shared), 0u);
  EXPECT_EQ(t.tet1(shared), 1u);
  EXPECT_FALSE(t.is_boundary(shared));
  // Vertex 0 is on 5 faces (3 of each tet, one shared), vertex 3 on 3.
  EXPECT_EQ(faces_on(t, 0), 5u);
  EXPECT_EQ(faces_on(t, 3), 3u);
  const ValidationReport r = validate(m, t);
  // Consistently wound neighbours: both positive.
  EXPECT_EQ(r.positive_tets, 2u);
  EXPECT_EQ(r.negative_tets, 0u);
  EXPECT_TRUE(r.clean());
}

TEST(Topology, GridCountsAndTetFaces) {
  for (uint32_t n : {1u, 2u, 5u}) {
    const TetMesh m = grid(n);
    const Topology t = build_topology(m);
    // Per cube: 5 tets; faces = (20 per cube + 2 per cube-face quad) / 2 ... easier
    // from Euler: boundary = 6 n^2 quads * 2 triangles; interior faces =
    // (4*5 n^3 - boundary) / 2.
    const size_t boundary = 12u * n * n;
    EXPECT_EQ(t.num_boundary_faces, boundary) << n;
    EXPECT_EQ(t.num_faces(), boundary + (20u * n * n * n - boundary) / 2) << n;
    EXPECT_TRUE(t.nonmanifold_faces.empty());
    // Every tet's four faces are faces of the topology, and point back.
    const auto tf = build_tet_faces(m, t);
    for (uint32_t ti = 0; ti < m.num_tets(); ++ti)
      for (uint32_t k = 0; k < 4; ++k) {
        const uint32_t f = tf[ti][k];
        ASSERT_LT(f, t.num_faces());
        EXPECT_EQ(t.face(f), Topology::tet_face(m.tets[ti], k));
        EXPECT_TRUE(t.tet0(f) == ti || t.tet1(f) == ti);
      }
    const ValidationReport r = validate(m, t);
    EXPECT_TRUE(r.clean()) << n;
    EXPECT_NEAR(r.volume, double(n) * n * n, 1e-9);
  }
}

TEST(Topology, NonManifoldFaceCounted) {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
  m.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}};
  const Topology t = build_topology(m);
  EXPECT_EQ(t.nonmanifold_faces.size(), 1u);
  EXPECT_EQ(validate(m, t).nonmanifold_faces, 1u);
}

TEST(Validate, CountsEveryAnomalyWithoutThrowing) {
  TetMesh m;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},  // a good tet
              {1, 1, 0},                                   // coplanar with 0,1,2
              {0, 0, 0},                                   // duplicate of 0
              {5, 5, 5},                                   // unused
              {nan, 0, 0}};                                // non-finite
  m.scalars = {0, 0, 0, 0, 0, 0, 0, std::numeric_limits<double>::infinity()};
  m.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 1, 3}, {0, 1, 2, 7}};
  const Topology t = build_topology(m);
  const ValidationReport r = validate(m, t);
  EXPECT_EQ(r.positive_tets, 1u);
  EXPECT_EQ(r.zero_volume_tets, 2u);  // the flat one and the repeated-index one
  EXPECT_EQ(r.repeated_index_tets, 1u);
  EXPECT_EQ(r.nonfinite_tets, 1u);
  EXPECT_EQ(r.duplicate_points, 1u);
  EXPECT_EQ(r.unused_points, 2u);  // 5 and 6
  EXPECT_EQ(r.nonfinite_points, 1u);
  EXPECT_EQ(r.nonfinite_scalars, 1u);
  EXPECT_FALSE(r.clean());
}

TEST(Validate, ZeroVolumeIsScaleInvariant) {
  for (double s : {1e-6, 1.0, 1e6}) {
    TetMesh m;
    // A sliver of relative height 1e-12 and a well-shaped tet, at scale s.
    m.points = {{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {s / 3, s / 3, 1e-12 * s}, {0, 0, s}};
    m.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}};
    const ValidationReport r = validate(m, build_topology(m));
    EXPECT_EQ(r.zero_volume_tets, 1u) << s;
    EXPECT_EQ(r.positive_tets, 1u) << s;
  }
}

// Two unit cubes side by side, split so the diagonals on their common face
// disagree: the face is a seam, boundary on both sides at the same place.
TEST(Validate, SeamOfMismatchedDiagonalsIsCoincidentBoundary) {
  TetMesh m;
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t j = 0; j < 2; ++j)
      for (uint32_t i = 0; i < 3; ++i) m.points.push_back({double(i), double(j), double(k)});
  append_hex_5tets(grid_hex(0, 0, 0, 3, 2), false, m.tets);
  append_hex_5tets(grid_hex(1, 0, 0, 3, 2), false, m.tets);  // same parity: mismatched
  Topology t = build_topology(m);
  ValidationReport r = validate(m, t);
  EXPECT_EQ(t.num_boundary_faces, 24u);  // 20 outer + 2 + 2 on the seam
  EXPECT_EQ(r.coincident_boundary_faces, 4u);

  // Alternating parity conforms: the seam disappears.
  m.tets.clear();
  append_hex_5tets(grid_hex(0, 0, 0, 3, 2), false, m.tets);
  append_hex_5tets(grid_hex(1, 0, 0, 3, 2), true, m.tets);
  t = build_topology(m);
  r = validate(m, t);
  EXPECT_EQ(t.num_boundary_faces, 20u);
  EXPECT_EQ(r.coincident_boundary_faces, 0u);
}

TEST(Validate, UnmergedDuplicatePointsMakeCoincidentFaces) {
  // Two tets touching along a face whose points are duplicated, not shared.
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
  m.tets = {{0, 1, 2, 3}, {4, 6, 5, 7}};
  const ValidationReport r = validate(m, build_topology(m));
  EXPECT_EQ(r.duplicate_points, 3u);
  EXPECT_EQ(r.coincident_boundary_faces, 2u);
}

TEST(DefaultMesh, IsAValidBall) {
  const TetMesh m = default_mesh(8);
  const Topology t = build_topology(m);
  const ValidationReport r = validate(m, t);
  EXPECT_TRUE(r.clean());
  EXPECT_EQ(m.num_tets(), 5u * 8 * 8 * 8);
  EXPECT_EQ(t.num_boundary_faces, 12u * 8 * 8);
  EXPECT_NEAR(r.volume, 4.0 / 3.0 * M_PI, 0.1);  // inscribed polytope, slightly smaller
  EXPECT_LT(r.volume, 4.0 / 3.0 * M_PI);
  for (const auto& p : m.points) EXPECT_LE(glm::length(p), 1.0 + 1e-12);
}

}  // namespace
}  // namespace zs
