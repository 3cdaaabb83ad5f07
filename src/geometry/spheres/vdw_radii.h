// Van der Waals radii by element, for drawing atoms as spheres.
#pragma once

#include <string_view>

namespace zs {

// Radius used for elements not in the table (and blank ones), in Å.
inline constexpr double kDefaultVdwRadius = 1.8;

// Bondi's radii (J. Phys. Chem. 68, 441, 1964), in Å, for the symbol as PDB
// writes it (case-insensitive, surrounding spaces ignored: " C", "FE", "Cl");
// hydrogen's isotopes D and T as H. Returns false for symbols Bondi does not
// list (most metals, e.g. Fe and Ca), leaving r untouched.
bool vdw_radius(std::string_view element, double& r);

}  // namespace zs
