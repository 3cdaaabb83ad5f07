// Sphere files by name: molecules (.pdb/.ent, .cif/.mmcif, each also .gz;
// molecule_reader.h), .sph (text sphere lists) and .sphb (binary sphere lists).
#pragma once

#include <string>

#include "geometry/spheres/molecule_reader.h"
#include "geometry/spheres/sphere_set.h"

namespace zs {

// True when the file name has a sphere format's extension (any case).
bool is_sphere_file(const std::string& path);
// Reads a sphere file by its extension (`molecule`: what a molecule file
// gives); throws FileError naming the file.
SphereSet read_sphere_file(const std::string& path, const MoleculeOptions& molecule = {});
// Writes .sph (text) or .sphb (binary) by the extension (any case), through
// AtomicFile; throws FileError naming the file, also for another extension.
void write_spheres(const std::string& path, const SphereSet& s);

}  // namespace zs
