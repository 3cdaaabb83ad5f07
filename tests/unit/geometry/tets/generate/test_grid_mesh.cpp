// make_grid_mesh (`mesh generate grid`, issue 41): counts, every tet
// positive, the box's volume exactly, a conforming split, jitter inside the
// box and within the bound proved safe here, the same mesh for any thread
// count, the brick order, and one-line errors.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "geometry/tets/generate/grid_mesh.h"
#include "geometry/tets/generate/scalar_fields.h"
#include "geometry/tets/hex_split.h"
#include "geometry/tets/topology.h"
#include "support/file_error_of.h"

using zs::test::thrown;

namespace {

using Cells = std::array<uint32_t, 3>;

zs::TetMesh grid(Cells cells, int split = 5, double jitter = 0, uint64_t seed = 1) {
  zs::GridMeshOptions o;
  o.cells = cells;
  o.split = split;
  o.jitter = jitter;
  o.seed = seed;
  return zs::make_grid_mesh(o);
}

// Grids with one cell, flat ones, non-cubic ones, and ones whose bricks of 8³
// do not divide them (partial bricks on every side).
const std::vector<Cells> kGrids = {{1, 1, 1}, {2, 1, 1}, {1, 3, 1}, {3, 2, 1}, {4, 3, 5}, {9, 10, 17}, {20, 8, 3}};

double cell_size(Cells c) { return 2.0 / std::max({c[0], c[1], c[2]}); }

double box_volume(Cells c) {
  const double h = cell_size(c);
  return c[0] * h * c[1] * h * c[2] * h;
}

zs::Tet sorted(zs::Tet t) {
  std::sort(t.begin(), t.end());
  return t;
}

bool same(const zs::TetMesh& a, const zs::TetMesh& b) {
  return a.points == b.points && a.tets == b.tets && a.scalars == b.scalars;
}

}  // namespace

TEST(GridMesh, CountsAndEveryCellOnceWhateverTheBricks) {
  for (int split : {5, 6})
    for (const Cells& c : kGrids) {
      SCOPED_TRACE(std::to_string(split) + "-split " + std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" +
                   std::to_string(c[2]));
      const zs::TetMesh m = grid(c, split);
      ASSERT_EQ(m.num_points(), size_t(c[0] + 1) * (c[1] + 1) * (c[2] + 1));
      ASSERT_EQ(m.num_tets(), size_t(split) * c[0] * c[1] * c[2]);
      EXPECT_FALSE(m.has_scalars());
      // The same tets as the plain i-fastest loop over the cells, in brick order.
      std::vector<zs::Tet> want;
      for (uint32_t k = 0; k < c[2]; ++k)
        for (uint32_t j = 0; j < c[1]; ++j)
          for (uint32_t i = 0; i < c[0]; ++i) {
            const zs::HexCorners h = zs::grid_hex(i, j, k, c[0] + 1, c[1] + 1);
            if (split == 5) zs::append_hex_5tets(h, (i + j + k) & 1, want);
            else zs::append_hex_6tets(h, want);
          }
      std::vector<zs::Tet> got;
      for (const zs::Tet& t : m.tets) got.push_back(sorted(t));
      for (zs::Tet& t : want) t = sorted(t);
      std::sort(got.begin(), got.end());
      std::sort(want.begin(), want.end());
      EXPECT_EQ(got, want);
    }
}

TEST(GridMesh, PointsInGridOrderCellsAreCubesLongestAxisSpansMinusOneToOne) {
  const Cells c{4, 2, 3};
  const zs::TetMesh m = grid(c);
  const double h = 0.5;
  for (uint32_t k = 0; k <= c[2]; ++k)
    for (uint32_t j = 0; j <= c[1]; ++j)
      for (uint32_t i = 0; i <= c[0]; ++i)
        ASSERT_EQ(m.points[zs::grid_node(i, j, k, c[0] + 1, c[1] + 1)],
                  glm::dvec3(-1 + i * h, -0.5 + j * h, -0.75 + k * h));
}

TEST(GridMesh, BricksKeepConsecutiveTetsOnNearbyPoints) {
  // 20³ cells: the first 8³ cells' tets use only the first brick's 9³ nodes.
  const zs::TetMesh m = grid({20, 20, 20});
  for (size_t t = 0; t < 5 * 512; ++t)
    for (uint32_t v : m.tets[t]) {
      const uint32_t i = v % 21, j = v / 21 % 21, k = v / (21 * 21);
      ASSERT_TRUE(i <= 8 && j <= 8 && k <= 8) << "tet " << t << " vertex " << v;
    }
}

TEST(GridMesh, EveryTetPositiveAndVolumesSumToTheBox) {
  for (int split : {5, 6})
    for (double jitter : {0.0, 0.1, zs::kMaxGridJitter})
      for (const Cells& c : kGrids) {
        SCOPED_TRACE(std::to_string(split) + "-split, jitter " + std::to_string(jitter) + ", " +
                     std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]));
        const zs::TetMesh m = grid(c, split, jitter, 7);
        const double h = cell_size(c);
        double sum = 0, least = INFINITY;
        for (const zs::Tet& t : m.tets) {
          const double v6 = zs::signed_volume6(m, t);
          sum += std::abs(v6) / 6;
          least = std::min(least, v6);
        }
        // At most the jitter bound's (1 - 6J) h³ lost from the smallest tets.
        EXPECT_GE(least, (1 - 6 * jitter) * h * h * h * (1 - 1e-9));
        EXPECT_NEAR(sum, box_volume(c), 1e-13 * box_volume(c));
      }
}

// The jitter bound, proved: a tet's signed volume is affine in each single
// coordinate of each vertex, so over a box of moves (±J h on each of the 12
// coordinates) it is least at one of the box's 4096 corners. Every tet shape
// the grid makes (both parities of the 5-split, all 6 Kuhn tets) appears in a
// 2³ grid; at kMaxGridJitter none can reach zero volume (fixing boundary
// nodes only shrinks the box), and at 1/6 some can.
TEST(GridMesh, JitterBoundIsProvedOverEveryCornerOfTheMoves) {
  auto least_over_moves = [](const zs::TetMesh& m, const zs::Tet& t, double move) {
    double least = INFINITY;
    for (uint32_t s = 0; s < 4096; ++s) {
      zs::TetMesh q;
      for (int v = 0; v < 4; ++v) {
        glm::dvec3 p = m.points[t[v]];
        for (int a = 0; a < 3; ++a) p[a] += (s >> (3 * v + a) & 1) ? move : -move;
        q.points.push_back(p);
      }
      least = std::min(least, zs::signed_volume6(q, {0, 1, 2, 3}));
    }
    return least;
  };
  for (int split : {5, 6}) {
    const zs::TetMesh m = grid({2, 2, 2}, split);  // cell size 1
    double at_max = INFINITY, at_sixth = INFINITY;
    for (const zs::Tet& t : m.tets) {
      at_max = std::min(at_max, least_over_moves(m, t, zs::kMaxGridJitter));
      at_sixth = std::min(at_sixth, least_over_moves(m, t, 1.0 / 6));
    }
    EXPECT_NEAR(at_max, 1 - 6 * zs::kMaxGridJitter, 1e-12) << split;
    EXPECT_GT(at_max, 0.03) << split;
    EXPECT_LE(at_sixth, 1e-12) << split;
  }
}

TEST(GridMesh, ConformingWithTheBoxAsBoundary) {
  for (int split : {5, 6})
    for (const Cells& c : kGrids) {
      SCOPED_TRACE(std::to_string(split) + "-split " + std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" +
                   std::to_string(c[2]));
      const zs::TetMesh m = grid(c, split, zs::kMaxGridJitter);
      const zs::Topology t = zs::build_topology(m);
      EXPECT_TRUE(t.nonmanifold_faces.empty());
      // Two triangles per boundary square, and every other face on two tets.
      const size_t boundary = 2 * 2 * (size_t(c[0]) * c[1] + size_t(c[1]) * c[2] + size_t(c[0]) * c[2]);
      EXPECT_EQ(t.num_boundary_faces, boundary);
      EXPECT_EQ(2 * (t.num_faces() - boundary) + boundary, 4 * m.num_tets());
      // Boundary faces lie in the box's faces.
      const zs::Bounds b = zs::bounds_of(m);
      size_t off_box = 0;
      for (uint32_t f = 0; f < t.num_faces(); ++f) {
        if (!t.is_boundary(f)) continue;
        bool on = false;
        for (int a = 0; a < 3; ++a)
          for (double side : {b.lo[a], b.hi[a]}) {
            bool all = true;
            for (uint32_t v : t.face(f)) all = all && m.points[v][a] == side;
            on = on || all;
          }
        off_box += !on;
      }
      EXPECT_EQ(off_box, 0u);
    }
}

TEST(GridMesh, JitterMovesOnlyInteriorNodesWithinTheBound) {
  const Cells c{6, 5, 4};
  const zs::TetMesh flat = grid(c), m = grid(c, 5, 0.15, 3);
  const double h = cell_size(c);
  size_t moved = 0;
  double most = 0;
  for (uint32_t k = 0; k <= c[2]; ++k)
    for (uint32_t j = 0; j <= c[1]; ++j)
      for (uint32_t i = 0; i <= c[0]; ++i) {
        const uint32_t v = zs::grid_node(i, j, k, c[0] + 1, c[1] + 1);
        const bool interior = i > 0 && i < c[0] && j > 0 && j < c[1] && k > 0 && k < c[2];
        if (!interior) {
          ASSERT_EQ(m.points[v], flat.points[v]) << i << " " << j << " " << k;
          continue;
        }
        for (int a = 0; a < 3; ++a) most = std::max(most, std::abs(m.points[v][a] - flat.points[v][a]));
        moved += m.points[v] != flat.points[v];
      }
  EXPECT_EQ(moved, size_t(c[0] - 1) * (c[1] - 1) * (c[2] - 1));
  EXPECT_LE(most, 0.15 * h);
  EXPECT_GT(most, 0.12 * h);  // 60 nodes × 3 axes spread over the range
  EXPECT_EQ(m.tets, flat.tets);
}

TEST(GridMesh, SameSeedSameMeshForAnyThreadCount) {
  auto make = [](int threads, uint64_t seed) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    zs::TetMesh m = grid({40, 33, 27}, 5, 0.1, seed);  // 36 bricks
    zs::apply_field(m, "gaussians", seed);
    return m;
  };
  const zs::TetMesh one = make(1, 9), two = make(2, 9), again = make(2, 9), other = make(2, 10);
  EXPECT_TRUE(same(one, two));
  EXPECT_TRUE(same(two, again));
  EXPECT_NE(one.points, other.points);
  EXPECT_EQ(one.tets, other.tets);
  // The other analytic fields too: the parallel loop gives the serial one's doubles.
  for (const char* f : {"radial", "linear", "sin"}) {
    zs::TetMesh a = one, b = one;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      zs::apply_field(a, f, 1);
    }
    zs::apply_field(b, f, 1);
    EXPECT_EQ(a.scalars, b.scalars) << f;
  }
}

TEST(GridMesh, CellsParseAndErrorsAreOneLine) {
  EXPECT_EQ(zs::parse_grid_cells("200"), (Cells{200, 200, 200}));
  EXPECT_EQ(zs::parse_grid_cells("200,100,50"), (Cells{200, 100, 50}));
  auto parse = [](const std::string& s) { return thrown<std::invalid_argument>([&] { zs::parse_grid_cells(s); }); };
  EXPECT_EQ(parse("2x"), "'2x' is not a number");
  EXPECT_EQ(parse(""), "'' is not a number");
  EXPECT_EQ(parse("1,,3"), "'' is not a number");
  EXPECT_EQ(parse("1.5"), "'1.5' is not a whole number");
  EXPECT_EQ(parse("0"), "0 is out of range: must be in [1, 4294967294]");
  EXPECT_EQ(parse("4,-1,4"), "-1 is out of range: must be in [1, 4294967294]");
  EXPECT_EQ(parse("5000000000"), "5000000000 is out of range: must be in [1, 4294967294]");
  EXPECT_EQ(parse("1,2"), "'1,2' has 2 numbers: expected N or NX,NY,NZ");

  auto make = [](zs::GridMeshOptions o) { return thrown<std::invalid_argument>([&] { zs::make_grid_mesh(o); }); };
  zs::GridMeshOptions o;
  o.split = 4;
  EXPECT_EQ(make(o), "split must be 5 or 6, not 4");
  o = {};
  o.jitter = 0.2;
  EXPECT_EQ(make(o), "jitter must be in [0, 0.16], not 0.2");
  o = {};
  o.cells = {0, 1, 1};
  EXPECT_EQ(make(o), "cells must be in [1, 4294967294]");
  o = {};
  o.cells = {2000, 2000, 2000};
  EXPECT_EQ(make(o), "grid 2000x2000x2000 cells: 8012006001 points, over the 4294967295 that 32-bit point ids allow; "
                     "use fewer cells");
  o.cells = {1, 1, 1000000000};
  o.split = 6;
  EXPECT_EQ(make(o), "grid 1x1x1000000000 cells: 6000000000 tets, over the 4294967295 that 32-bit tet ids allow; "
                     "use fewer cells");
  o = {};
  o.cells = {100, 100, 100};
  o.memory_budget = 1 << 20;
  // 1030301 points × 32 bytes + 5 M tets × 16 bytes.
  EXPECT_EQ(make(o), "grid 100x100x100 cells: 1030301 points and 5000000 tets take 107.7 MiB, over the memory budget "
                     "of 1.0 MiB; use fewer cells");
}
