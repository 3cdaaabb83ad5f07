// A set of spheres (atoms, particles) for the sphere-sprite renderer: centres,
// radii, and optionally a scalar, an RGBA colour or a chemical element each.
// Filled by the molecule reader (.pdb, .cif and their .gz), the .sph and
// binary sphere readers and by the generators.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace zs {

// What a residue is, for colouring by residue type (sphere_colors.h): the
// twenty standard amino acids by side chain, then other residues by kind.
enum class ResidueClass : uint8_t { Hydrophobic, Polar, Acidic, Basic, OtherAminoAcid, Nucleic, Water, Other };
inline constexpr int kResidueClasses = 8;

// What a molecule file held and what the reader did (molecule_reader.h);
// printed by `mesh info`. Empty (atoms 0) for sets that are not molecules.
struct MoleculeCounts {
  size_t atoms = 0;           // drawn (after the model, altloc, water and hydrogen choices)
  size_t models = 0;          // in the file
  std::string model;          // the one read (its MODEL number)
  size_t chains = 0, residues = 0, waters = 0, hydrogens = 0;  // among the atoms drawn (waters: atoms)
  size_t waters_left_out = 0, hydrogens_left_out = 0;          // atoms
  size_t altlocs_left_out = 0;     // atoms of alternate locations not kept
  size_t elements_inferred = 0;    // from the atom name (no element in the file)
  size_t element_columns_cleared = 0, charge_columns_cleared = 0;  // PDB columns 77-80 that held no element/charge
  size_t unknown_elements = 0;     // drawn with kDefaultVdwRadius
  std::vector<std::pair<std::string, size_t>> elements;  // symbol, atoms; most first
};

struct SphereSet {
  std::vector<glm::dvec3> centres;
  std::vector<double> radii;
  std::vector<double> scalars;  // one per sphere, or empty (no scalar)
  std::string scalar_name;      // e.g. "b_factor"; empty when there is no scalar
  std::vector<glm::vec4> rgba;  // one per sphere (colour and opacity in [0, 1]), or empty
  std::vector<uint8_t> element; // atomic number per sphere (0: unknown), or empty (not atoms)
  // Molecules: per atom, its chain (an index into chain_names) and its
  // residue's class; empty for other sets.
  std::vector<uint16_t> chain;
  std::vector<std::string> chain_names;
  std::vector<ResidueClass> residue_class;
  MoleculeCounts molecule;

  // Records read but left out (alternate locations, waters and hydrogens not asked for).
  size_t skipped = 0;
  // Spheres left out because they cannot be drawn: zero, negative or
  // non-finite radius, non-finite centre.
  size_t invalid = 0;
  // Spheres kept but degenerate: a non-finite scalar.
  size_t degenerate = 0;
  // What a reader did that a user should know; printed by `mesh info`.
  std::vector<std::string> notes;

  size_t size() const { return centres.size(); }
  bool has_scalars() const { return !scalars.empty(); }
  bool has_rgba() const { return !rgba.empty(); }
  bool has_elements() const { return !element.empty(); }
  bool is_molecule() const { return !chain.empty(); }
};

}  // namespace zs
