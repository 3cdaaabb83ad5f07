// Sphere files by name: .pdb/.ent (atoms) and .sph (plain sphere lists).
#pragma once

#include <string>

#include "spheres/sphere_set.h"

namespace zs {

// True when the file name has a sphere format's extension (any case).
bool is_sphere_file(const std::string& path);
// Reads a sphere file by its extension; throws FileError naming the file.
SphereSet read_sphere_file(const std::string& path);

}  // namespace zs
