// `zsweep mesh info` for sphere files (molecules, .sph, .sphb): counts, bounds
// and radius range instead of the tet report; for a molecule also its atoms,
// elements, chains, residues, models, waters and hydrogens, what was inferred
// and what was left out (`molecule` chooses what is read).
#pragma once

#include <string>

#include "geometry/spheres/molecule_reader.h"

namespace zs {

void print_sphere_info(const std::string& path, bool json, const MoleculeOptions& molecule = {});

}  // namespace zs
