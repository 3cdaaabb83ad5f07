// Implicit solids for CGAL Mesh_3: f(p) < 0 inside. Kept free of CGAL so the
// functions are cheap to compile and test.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

struct ImplicitShape {
  std::string name;
  std::string description;
  std::function<double(const glm::dvec3&)> f;  // < 0 inside
  double bounding_radius;                       // origin-centred sphere containing the solid
};

const std::vector<ImplicitShape>& implicit_catalog();
const ImplicitShape* find_implicit(const std::string& name);  // nullptr if unknown

}  // namespace zs
