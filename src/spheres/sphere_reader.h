// The plain sphere list `.sph`: '#' comment lines and blank lines anywhere,
// otherwise one sphere per line
//   x y z r [scalar]
// with the scalar on every sphere line or on none.
#pragma once

#include <string>
#include <string_view>

#include "spheres/sphere_set.h"

namespace zs {

// Throws FileError naming the file and line: a wrong number of fields, a
// token that is not a number, a non-finite coordinate, a negative or
// non-finite radius, no spheres at all. A zero radius or a non-finite scalar
// is kept and counted as degenerate.
SphereSet parse_spheres(std::string_view text, const std::string& name);
SphereSet read_spheres(const std::string& path);

}  // namespace zs
