// Classic tetrahedral OFF, as used by the ZSweep lineage:
//   n_verts n_tets        (on one line or two)
//   x y z s               n_verts lines
//   a b c d               n_tets lines, 0-based
// '#' comment lines and blank lines are allowed anywhere.
#pragma once

#include <string>
#include <string_view>

#include "geometry/tets/tet_mesh.h"

namespace zs {

TetMesh read_off(const std::string& path);
// Parses text already in memory; `name` is used in error messages.
TetMesh parse_off(std::string_view text, const std::string& name);
void write_off(const std::string& path, const TetMesh& m);

}  // namespace zs
