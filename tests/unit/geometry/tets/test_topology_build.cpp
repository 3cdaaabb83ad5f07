// The parallel topology build (topology.h) against a plain reference built
// with a map: the same faces in the same order, the same tets on each, the
// same boundary and non-manifold faces — on grids, on shuffled numberings,
// on meshes with repeated indices, flat and non-manifold tets, and on any
// thread count.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "support/test_meshes.h"

namespace zs {
namespace {

struct RefFace {
  std::array<uint32_t, 3> v;
  std::vector<uint32_t> recs;  // tet << 2 | k, ascending
};

// Faces in (a, b, c) order with every record, from a std::map.
std::vector<RefFace> reference_faces(const TetMesh& m) {
  std::map<std::array<uint32_t, 3>, std::vector<uint32_t>> faces;
  for (uint32_t t = 0; t < m.num_tets(); ++t)
    for (uint32_t k = 0; k < 4; ++k) faces[Topology::tet_face(m.tets[t], k)].push_back(t << 2 | k);
  std::vector<RefFace> out;
  for (auto& [v, recs] : faces) out.push_back({v, recs});
  return out;
}

void expect_same(const TetMesh& m, const Topology& t, const char* what) {
  const std::vector<RefFace> ref = reference_faces(m);
  ASSERT_EQ(t.num_faces(), ref.size()) << what;
  size_t boundary = 0;
  std::vector<uint32_t> nonmanifold;
  for (uint32_t f = 0; f < ref.size(); ++f) {
    const RefFace& r = ref[f];
    ASSERT_EQ(t.face(f), r.v) << what << " face " << f;
    ASSERT_EQ(t.face_tets[f].first, r.recs[0]) << what << " face " << f;
    ASSERT_EQ(t.tet1(f), r.recs.size() > 1 ? r.recs[1] >> 2 : kNoTet) << what << " face " << f;
    boundary += r.recs.size() == 1;
    if (r.recs.size() > 2) nonmanifold.push_back(f);
  }
  EXPECT_EQ(t.num_boundary_faces, boundary) << what;
  EXPECT_EQ(t.nonmanifold_faces, nonmanifold) << what;
  ASSERT_EQ(t.tet_degenerate.size(), m.num_tets()) << what;
  EXPECT_EQ(t.num_nonfinite_tets, count_nonfinite_tets(m)) << what;
}

TetMesh grid_mesh(int n) {
  return test::box_mesh({n, n, n}, glm::dvec3(0), glm::dvec3(n), [](const glm::dvec3&) { return 1.0; });
}

// The same mesh with its points renumbered, its tets reordered and each
// tet's vertices rotated (orientation kept: an even permutation).
TetMesh shuffled(const TetMesh& m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> perm(m.num_points());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  TetMesh s;
  s.points.resize(m.num_points());
  s.scalars.resize(m.scalars.size());
  for (uint32_t v = 0; v < m.num_points(); ++v) {
    s.points[perm[v]] = m.points[v];
    if (m.has_scalars()) s.scalars[perm[v]] = m.scalars[v];
  }
  for (const Tet& t : m.tets) {
    const Tet p = {perm[t[0]], perm[t[1]], perm[t[2]], perm[t[3]]};
    static constexpr int kEven[3][4] = {{0, 1, 2, 3}, {1, 2, 0, 3}, {2, 0, 1, 3}};
    const int* r = kEven[rng() % 3];
    s.tets.push_back({p[r[0]], p[r[1]], p[r[2]], p[r[3]]});
  }
  std::shuffle(s.tets.begin(), s.tets.end(), rng);
  return s;
}

Topology build_on(const TetMesh& m, int threads) {
  Topology t;
  tbb::task_arena(threads).execute([&] { t = build_topology(m); });
  return t;
}

TEST(TopologyBuild, MatchesTheReferenceOnAnyThreadCount) {
  for (int n : {1, 3, 12}) {
    const TetMesh m = grid_mesh(n);
    for (int threads : {1, 2, 4}) expect_same(m, build_on(m, threads), "grid");
  }
}

TEST(TopologyBuild, ShuffledNumberingsGiveTheSameFaceSets) {
  const TetMesh m = grid_mesh(6);
  const Topology t = build_topology(m);
  for (uint32_t seed : {1u, 2u}) {
    const TetMesh s = shuffled(m, seed);
    const Topology ts = build_on(s, 2);
    expect_same(s, ts, "shuffled");
    // Same counts, and every face of the original is a face of the shuffle
    // with the same number of tets on it.
    EXPECT_EQ(ts.num_faces(), t.num_faces());
    EXPECT_EQ(ts.num_boundary_faces, t.num_boundary_faces);
  }
}

TEST(TopologyBuild, RepeatedIndicesFlatAndNonManifoldTets) {
  std::mt19937 rng(7);
  TetMesh m;
  for (int i = 0; i < 40; ++i) m.points.push_back({double(rng() % 5), double(rng() % 5), double(rng() % 5)});
  m.scalars.assign(40, 1.0);
  m.points[3].y = INFINITY;  // non-finite tets, counted
  m.scalars[5] = NAN;
  // Random tets over few points: many shared, repeated and non-manifold faces.
  for (int i = 0; i < 3000; ++i)
    m.tets.push_back({uint32_t(rng() % 40), uint32_t(rng() % 40), uint32_t(rng() % 40), uint32_t(rng() % 40)});
  for (int threads : {1, 2, 3}) {
    const Topology t = build_on(m, threads);
    expect_same(m, t, "random");
    EXPECT_FALSE(t.nonmanifold_faces.empty());
    EXPECT_GT(t.num_nonfinite_tets, 0u);
  }
}

TEST(TopologyBuild, EmptyMeshAndUnusedPoints) {
  TetMesh m;
  expect_same(m, build_topology(m), "empty");
  m.points.assign(10, glm::dvec3(0));
  expect_same(m, build_topology(m), "points only");
}

}  // namespace
}  // namespace zs
