// Atoms of a Protein Data Bank (.pdb) file as spheres.
#pragma once

#include <string>
#include <string_view>

#include "geometry/spheres/sphere_set.h"

namespace zs {

// Reads the ATOM and HETATM records of model 1 (up to the first ENDMDL; other
// records are ignored) by the format's fixed columns: x 31-38, y 39-46,
// z 47-54, alternate location 17, B-factor 61-66, element 77-78. The radius
// is the element's van der Waals radius (vdw_radii.h); a blank element
// field falls back to the atom name (columns 13-16). The same symbol gives
// each atom's atomic number (SphereSet::element; 0 when unknown). Alternate locations
// other than the first one seen are skipped and counted. The B-factor is the
// scalar when every atom has one. Throws FileError naming the file and line
// for a record too short for its coordinates, a coordinate that is not a
// number or not finite, and for a file without atoms.
SphereSet parse_pdb(std::string_view text, const std::string& name);
SphereSet read_pdb(const std::string& path);

}  // namespace zs
