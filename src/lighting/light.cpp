#include "lighting/light.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

glm::dvec3 to_light(const Light& l, const glm::dvec3& p) {
  if (l.type == LightType::Directional) return -glm::normalize(l.direction);
  return glm::normalize(l.position - p);
}

bool in_light_cone(const Light& l, const glm::dvec3& p) {
  if (l.type == LightType::Directional) return true;
  const glm::dvec3 d = p - l.position;
  const double len = glm::length(d);
  if (!(len > 0)) return false;
  const glm::dvec3 axis = glm::normalize(l.target - l.position);
  return glm::dot(d, axis) >= len * std::cos(0.5 * l.fov_deg * M_PI / 180.0);
}

}  // namespace zs
