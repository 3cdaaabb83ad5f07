// TetGen .node / .ele files, read and written through the TetGen library.
// Either name may be given; the other is found by replacing the extension.
// The scalar travels as the first point attribute in .node.
#pragma once

#include <string>

#include "geometry/tets/tet_mesh.h"

namespace zs {

TetMesh read_tetgen(const std::string& path);
void write_tetgen(const std::string& path, const TetMesh& m);

}  // namespace zs
