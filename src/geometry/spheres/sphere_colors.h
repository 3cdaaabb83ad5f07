// The colour and opacity each sphere is drawn with (the scene's
// `spheres.color`): by chemical element (atoms), by the file's own RGBA, by
// scalar through the scene's transfer function (colour and opacity; a
// molecule's B-factor), or, for molecules, by chain or by residue type.
#pragma once

#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "base/optics/transfer_function.h"
#include "geometry/spheres/sphere_set.h"

namespace zs {

enum class SphereColorMode { Element, Rgba, Scalar, Chain, Residue };
const char* to_string(SphereColorMode m);
bool parse_sphere_color_mode(const std::string& s, SphereColorMode* out);

// What a set is coloured by when the scene does not say: its RGBA when it has
// one, else its elements, else its scalar, else element (uniform grey for
// unknown elements).
SphereColorMode default_color_mode(const SphereSet& s);

// The colour of an element by atomic number (Jmol/CPK convention; 0 or
// unknown: grey), opacity 1.
glm::vec4 element_color(unsigned atomic_number);

// A chain's colour: kChainPalette[chain index % kChainColors] (chains in the
// order the file first names them), opacity 1.
inline constexpr int kChainColors = 12;
glm::vec4 chain_color(unsigned chain_index);
// A residue class's colour (docs/spheres.md has the table), opacity 1.
glm::vec4 residue_color(ResidueClass c);

// One RGBA per sphere (a non-finite scalar: grey, opaque). Throws std::runtime_error when the set lacks what the
// mode needs (no RGBA, no scalar; chain and residue: not a molecule).
std::vector<glm::vec4> sphere_colors(const SphereSet& s, SphereColorMode mode, const TransferFunction& tf);

}  // namespace zs
