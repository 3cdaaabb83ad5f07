#include "geometry/tets/hex_split.h"

namespace zs {

void append_hex_5tets(const HexCorners& c, bool odd, std::vector<Tet>& out) {
  // Even parity: corners 0,2,5,7 form the central tet and 1,3,4,6 are cut
  // off. Odd parity uses the other diagonal set (1,3,4,6 central). Each of the
  // six quad faces is then split along the diagonal its neighbour also uses.
  if (!odd) {
    out.push_back({c[0], c[1], c[2], c[5]});
    out.push_back({c[0], c[2], c[3], c[7]});
    out.push_back({c[0], c[5], c[7], c[4]});
    out.push_back({c[2], c[7], c[5], c[6]});
    out.push_back({c[0], c[2], c[7], c[5]});
  } else {
    out.push_back({c[1], c[2], c[3], c[6]});
    out.push_back({c[0], c[1], c[3], c[4]});
    out.push_back({c[1], c[4], c[6], c[5]});
    out.push_back({c[3], c[6], c[4], c[7]});
    out.push_back({c[1], c[3], c[4], c[6]});
  }
}

void append_hex_6tets(const HexCorners& c, std::vector<Tet>& out) {
  // One tet per path 0 -> 6 along the cube's edges (x, y, z in each order):
  // every face is then cut along the diagonal from its corner nearest
  // corner 0, which is also the diagonal its neighbour cuts. Odd orders of
  // the axes are negative as walked; their middle two corners are swapped.
  out.push_back({c[0], c[1], c[2], c[6]});  // x y z
  out.push_back({c[0], c[3], c[7], c[6]});  // y z x
  out.push_back({c[0], c[4], c[5], c[6]});  // z x y
  out.push_back({c[0], c[5], c[1], c[6]});  // x z y
  out.push_back({c[0], c[2], c[3], c[6]});  // y x z
  out.push_back({c[0], c[7], c[4], c[6]});  // z y x
}

HexCorners grid_hex(uint32_t i, uint32_t j, uint32_t k, uint32_t ni, uint32_t nj) {
  return {grid_node(i, j, k, ni, nj),         grid_node(i + 1, j, k, ni, nj),
          grid_node(i + 1, j + 1, k, ni, nj), grid_node(i, j + 1, k, ni, nj),
          grid_node(i, j, k + 1, ni, nj),     grid_node(i + 1, j, k + 1, ni, nj),
          grid_node(i + 1, j + 1, k + 1, ni, nj), grid_node(i, j + 1, k + 1, ni, nj)};
}

}  // namespace zs
