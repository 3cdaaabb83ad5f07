// The plain sphere list `.sph`: '#' comment lines and blank lines anywhere,
// otherwise one sphere per line, in one of three forms (the same on every
// sphere line):
//   x y z r               4 fields
//   x y z r scalar        5 fields
//   x y z r R G B A       8 fields, colour and opacity in [0, 1]
// The binary form of the same data is `.sphb` (sphere_binary.h).
#pragma once

#include <string>
#include <string_view>

#include "geometry/spheres/sphere_set.h"

namespace zs {

// Spheres with a zero, negative or non-finite radius or a non-finite centre
// are skipped and counted (SphereSet::invalid). A non-finite scalar is kept
// and counted as degenerate. Throws FileError naming the file and line: a
// field count other than 4, 5 or 8, a count unlike the first sphere line's, a
// token that is not a number, an R, G, B or A outside [0, 1] or not finite;
// and naming the file: no sphere lines at all, or none that is drawable.
SphereSet parse_spheres(std::string_view text, const std::string& name);
SphereSet read_spheres(const std::string& path);

}  // namespace zs
