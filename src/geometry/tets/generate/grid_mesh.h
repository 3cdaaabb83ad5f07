// `mesh generate grid` (issue 41): a box of NX × NY × NZ cubes, each split
// into 5 or 6 tets, conforming and positive, in seconds at 100 M tets. Built
// in parallel straight into pre-sized arrays, the same mesh for any thread
// count.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "geometry/tets/tet_mesh.h"

namespace zs {

// The largest jitter. Moving the four corners of a tet by up to J cell sizes
// per axis can flatten it from J = 1/6 on (the corner tets of the 5-split and
// every Kuhn tet, whose six-fold volume drops to (1 - 6J) h³ at worst;
// test_grid_mesh.cpp proves it over every corner of the jitter box); 0.16
// keeps at least 4 % of that volume.
inline constexpr double kMaxGridJitter = 0.16;

struct GridMeshOptions {
  std::array<uint32_t, 3> cells{1, 1, 1};  // NX, NY, NZ
  // 5: hex_split.h's alternating 5-tet split; 6: the Kuhn split of every cube
  // around its diagonal from (i, j, k) to (i+1, j+1, k+1).
  int split = 5;
  // Interior nodes (not on the box) move by up to jitter × cell size per
  // axis, by a hash of (node, seed): in [0, kMaxGridJitter].
  double jitter = 0;
  uint64_t seed = 1;
  // Bytes the mesh (points, scalars, tets) may take; 0 = default_memory_budget().
  uint64_t memory_budget = 0;
};

// "200" (a cube) or "200,100,50". Throws std::invalid_argument with a
// message to follow "--cells: ", e.g. "'2x' is not a number".
std::array<uint32_t, 3> parse_grid_cells(const std::string& text);

// The mesh: cells are cubes, the longest axis spans [-1, 1] and the others
// proportionally, centred on 0. Points in grid order (i fastest); cells in
// bricks of 8³ (bricks i fastest, cells i fastest inside), so consecutive tets
// touch nearby points. No scalars. Throws std::invalid_argument (one line)
// for a bad split or jitter, counts over 32-bit ids, or a mesh over the memory
// budget.
TetMesh make_grid_mesh(const GridMeshOptions& o);

}  // namespace zs
