// Splitting a structured grid of hexahedra into tets: 5 per hex, with the
// split alternating by the parity of (i+j+k) so that the diagonals chosen on a
// face shared by two neighbouring hexes agree and the mesh conforms; or 6 per
// hex around its main diagonal (Kuhn/Freudenthal), conforming when every hex
// uses the same one.
#pragma once

#include <array>
#include <cstdint>

#include "geometry/tets/tet_mesh.h"

namespace zs {

// Corners in VTK hexahedron order: 0..3 the bottom quad (i,j,k), (i+1,j,k),
// (i+1,j+1,k), (i,j+1,k); 4..7 the same at k+1.
using HexCorners = std::array<uint32_t, 8>;

// Appends the 5 tets of one hex; `odd` = (i+j+k) & 1.
void append_hex_5tets(const HexCorners& c, bool odd, std::vector<Tet>& out);

// Appends the 6 tets of one hex around its diagonal from corner 0 to corner
// 6, each positive on a right-handed hex (corners as above with i, j, k along
// x, y, z).
void append_hex_6tets(const HexCorners& c, std::vector<Tet>& out);

// Point id of grid node (i, j, k) in a grid of ni × nj × nk nodes, i fastest.
inline uint32_t grid_node(uint32_t i, uint32_t j, uint32_t k, uint32_t ni, uint32_t nj) {
  return i + ni * (j + nj * k);
}

// Corners of cell (i, j, k) in a node grid of ni × nj (× any) nodes.
HexCorners grid_hex(uint32_t i, uint32_t j, uint32_t k, uint32_t ni, uint32_t nj);

}  // namespace zs
