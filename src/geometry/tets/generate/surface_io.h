// Closed triangle surfaces (.off/.stl/.ply/.obj) read through CGAL's polygon
// soup readers, as a PLC for TetGen.
#pragma once

#include <string>

#include "geometry/tets/generate/plc.h"

namespace zs {

// Polygons with more than three corners are fan-triangulated. Throws
// zs::FileError naming the file when it cannot be read, is empty, or is not
// closed (every edge must be shared by exactly two triangles).
Plc read_surface(const std::string& path);

}  // namespace zs
