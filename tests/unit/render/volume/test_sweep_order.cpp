// The sweep's projection order (sweep_order.h) against a plain sort: every
// face that can produce a fragment, by (rank of its first swept vertex, face
// id), with its plane depth and single tile; the same on any thread count.
#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "geometry/tets/topology.h"
#include "render/volume/sweep_order.h"
#include "support/test_meshes.h"

namespace zs {
namespace {

struct Case {
  TetMesh mesh;
  Topology topo;
  std::vector<ScreenVertex> sv;
  std::vector<FaceClass> cls;
  std::vector<uint8_t> done;
  std::vector<SweepEvent> events;
  std::vector<NearTriangle> near;
};

// Random screen positions (some off the image, some repeated so faces come
// out edge-on), depths with many ties, some culled and done faces, and
// vertices that are not events.
Case make_case(glm::ivec3 cells, uint32_t seed, bool with_done) {
  Case c;
  c.mesh = test::box_mesh(cells, {0, 0, 0}, {1, 1, 1}, [](const glm::dvec3&) { return 0.0; });
  c.topo = build_topology(c.mesh);
  std::mt19937 rng(seed);
  const size_t nv = c.mesh.num_points();
  for (uint32_t v = 0; v < nv; ++v) {
    double x = double(rng() % 1000) / 10.0 - 10.0, y = double(rng() % 800) / 10.0 - 10.0;
    if (rng() % 20 == 0) x = y = 5.0;  // shared positions: degenerate faces
    c.sv.push_back({x, y, double(rng() % 40) * 0.5 + 1.0, 0.0, v});
  }
  for (uint32_t v = 0; v < nv; ++v)
    if (rng() % 8 != 0) c.events.push_back({c.sv[v].z, v});
  std::shuffle(c.events.begin(), c.events.end(), rng);
  for (size_t f = 0; f < c.topo.num_faces(); ++f) c.cls.push_back(FaceClass(rng() % 4));
  if (with_done)
    for (size_t f = 0; f < c.topo.num_faces(); ++f) c.done.push_back(rng() % 10 == 0);
  c.near.push_back({{{1, 1, 1, 0, 0}, {30, 2, 1, 0, 1}, {3, 40, 1, 0, 2}}, FaceClass::Entry});
  c.near.push_back({{{1, 1, 1, 0, 0}, {1, 1, 1, 0, 1}, {3, 40, 1, 0, 2}}, FaceClass::Entry});  // flat
  return c;
}

TEST(SweepOrder, MatchesAPlainSortOnAnyThreadCount) {
  const ScreenTiling tiling{80, 60, 16};
  for (auto [cells, seed, with_done] : {std::tuple{glm::ivec3{3, 2, 2}, 1u, false}, std::tuple{glm::ivec3{14, 13, 12}, 2u, true},
                                        std::tuple{glm::ivec3{24, 20, 22}, 3u, false}}) {
    const Case c = make_case(cells, seed, with_done);
    const double z_origin = 0.75;
    // The reference: ranks from a plain sort of the events, then every kept
    // face with its key, sorted.
    std::vector<SweepEvent> ev = c.events;
    std::sort(ev.begin(), ev.end(), [](auto& a, auto& b) { return a.z < b.z || (a.z == b.z && a.v < b.v); });
    std::vector<uint32_t> rank(c.sv.size(), UINT32_MAX);
    for (uint32_t i = 0; i < ev.size(); ++i) rank[ev[i].v] = i;
    std::vector<std::tuple<uint32_t, uint32_t, uint32_t>> want;  // rank, face, tile
    uint64_t degenerate = 1, offscreen = 0;                       // the flat near triangle
    for (uint32_t f = 0; f < c.topo.num_faces(); ++f) {
      if ((!c.done.empty() && c.done[f]) || c.cls[f] == FaceClass::Culled) continue;
      const auto fv = c.topo.face(f);
      const uint32_t rk = std::min({rank[fv[0]], rank[fv[1]], rank[fv[2]]});
      if (rk == UINT32_MAX) continue;
      const ScreenVertex v[3] = {c.sv[fv[0]], c.sv[fv[1]], c.sv[fv[2]]};
      if (screen_det(v) == 0) {
        ++degenerate;
        continue;
      }
      int i0, i1, j0, j1;
      if (!pixel_range(v, tiling.width, tiling.height, &i0, &i1, &j0, &j1)) {
        ++offscreen;
        continue;
      }
      want.push_back({rk, f, single_tile(item_tile_box(v, tiling), tiling)});
    }
    std::sort(want.begin(), want.end());
    ASSERT_GT(want.size(), 10u);
    for (int threads : {1, 2, 4}) {
      SweepItems got;
      tbb::task_arena(threads).execute(
          [&] { got = sweep_order(c.topo, c.sv, c.cls, c.done, c.events, c.near, z_origin, tiling); });
      EXPECT_EQ(got.degenerate, degenerate);
      EXPECT_EQ(got.offscreen, offscreen);
      ASSERT_EQ(got.size(), want.size() + 1) << threads;
      EXPECT_EQ(got[0].id, kNearItem | 0u);
      EXPECT_EQ(got[0].z_sweep, -INFINITY);
      for (size_t k = 0; k < want.size(); ++k) {
        const auto [rk, f, tile] = want[k];
        ASSERT_EQ(got[k + 1].id, f) << threads << " " << k;
        ASSERT_EQ(got[k + 1].z_sweep, float(ev[rk].z - z_origin)) << k;
        ASSERT_EQ(got[k + 1].tile, tile) << k;
      }
    }
  }
}

}  // namespace
}  // namespace zs
