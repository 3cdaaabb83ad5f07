// A set of spheres (atoms, particles) for the sphere-sprite renderer: centres,
// radii, and optionally a scalar, an RGBA colour or a chemical element each.
// Filled by the .pdb, .sph and binary sphere readers and by the generators.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace zs {

struct SphereSet {
  std::vector<glm::dvec3> centres;
  std::vector<double> radii;
  std::vector<double> scalars;  // one per sphere, or empty (no scalar)
  std::string scalar_name;      // e.g. "b_factor"; empty when there is no scalar
  std::vector<glm::vec4> rgba;  // one per sphere (colour and opacity in [0, 1]), or empty
  std::vector<uint8_t> element; // atomic number per sphere (0: unknown), or empty (not atoms)

  // Records read but left out (PDB alternate locations after the first).
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
};

}  // namespace zs
