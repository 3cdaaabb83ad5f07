// Writes a sphere set as `.sph` text (sphere_reader.h reads it back).
#pragma once

#include <string>

#include "geometry/spheres/sphere_set.h"

namespace zs {

// The text of a .sph file: a '#' line naming the fields, then one sphere per
// line with the fields sphere_fields() picks (RGBA, else scalar, else none).
// A value that is exactly a float32 is written with the fewest digits that
// read back (as a double, rounded to float) as that float, so
// .sphb -> .sph -> .sphb is bit-exact and the text short; any other double
// with the fewest digits that read back as exactly that double.
std::string format_spheres_text(const SphereSet& s);

// The same into a file, through AtomicFile (nothing left on failure);
// throws FileError naming the file.
void write_spheres_text(const std::string& path, const SphereSet& s);

}  // namespace zs
