// A set of spheres (atoms, particles) for the sphere-sprite renderer: centres,
// radii and an optional scalar each. Filled by the .pdb and .sph readers.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

struct SphereSet {
  std::vector<glm::dvec3> centres;
  std::vector<double> radii;
  std::vector<double> scalars;  // one per sphere, or empty (no scalar)
  std::string scalar_name;      // e.g. "b_factor"; empty when there is no scalar

  // Records read but left out (PDB alternate locations after the first).
  size_t skipped = 0;
  // Spheres kept but degenerate: zero radius, or a non-finite scalar.
  size_t degenerate = 0;
  // What a reader did that a user should know; printed by `mesh info`.
  std::vector<std::string> notes;

  size_t size() const { return centres.size(); }
  bool has_scalars() const { return !scalars.empty(); }
};

}  // namespace zs
