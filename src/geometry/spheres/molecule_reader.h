// Molecules as spheres, read through gemmi (the library structural
// biologists use): PDB (.pdb, .ent) and mmCIF/PDBx (.cif, .mmcif), each also
// gzipped (.gz). One sphere per atom at its van der Waals radius
// (vdw_radii.h: Bondi's table; unknown elements drawn at kDefaultVdwRadius
// and counted). The element comes from the file's element field, else from
// the atom name as the PDB format defines it (gemmi: " CA " is a carbon
// alpha, "CA  " calcium). HETATM records are kept. Alternate locations: the
// first one the file names (usually 'A') is kept, the others counted. The
// B-factor is the scalar when every atom has one. docs/spheres.md says what
// is tolerated.
#pragma once

#include <string>
#include <string_view>

#include "geometry/spheres/sphere_set.h"

namespace zs {

struct MoleculeOptions {
  std::string model;       // MODEL number to read; "" = the first model in the file
  bool waters = true;      // keep water molecules (HOH, WAT, ...)
  bool hydrogens = true;   // keep hydrogen (and deuterium) atoms
};

enum class MoleculeFormat { Pdb, Mmcif };

// True for the molecule files read_molecule takes, by name.
bool is_molecule_file(const std::string& path);

// Throws FileError naming the file (and the line where the format gives
// one) for malformed or truncated files, a model the file does not have, and
// a file (or choice) without atoms.
SphereSet read_molecule(const std::string& path, const MoleculeOptions& opt = {});
SphereSet parse_molecule(std::string_view text, const std::string& name, MoleculeFormat format,
                         const MoleculeOptions& opt = {});
// PDB text (the tests' and the fuzzer's entry).
inline SphereSet parse_pdb(std::string_view text, const std::string& name) {
  return parse_molecule(text, name, MoleculeFormat::Pdb);
}

}  // namespace zs
