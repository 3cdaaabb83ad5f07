// Closed boundaries (PLCs) for the synthetic shapes `mesh generate` offers,
// built at a resolution suited to tets of edge length about h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/tets/generate/plc.h"

namespace zs {

struct ShapeInfo {
  std::string name;
  std::string description;
  double volume;     // (approximate) enclosed volume, for the -a estimate
  bool curved;       // curved boundary: preserve the fitted surface (-Y)
};

const std::vector<ShapeInfo>& shape_catalog();
const ShapeInfo* find_shape(const std::string& name);  // nullptr if unknown

// Throws std::invalid_argument for an unknown name. `seed` only affects the
// randomised shapes (blob).
Plc make_shape(const std::string& name, double h, uint64_t seed);

// Building blocks, exposed for tests.
// Geodesic sphere (icosahedron, each edge split in `freq`), scaled to an
// ellipsoid with the given radii.
Plc ellipsoid_surface(const glm::dvec3& centre, const glm::dvec3& radii, int freq);
Plc torus_surface(double major, double minor, int n_major, int n_minor);
Plc box_surface(const glm::dvec3& lo, const glm::dvec3& hi);
// Appends b's points and facets (and holes) to a.
void append_plc(Plc& a, const Plc& b);

}  // namespace zs
