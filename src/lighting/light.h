// The lights a shadow map is cast from. A directional light's `direction` is
// the way its light travels (from the light into the scene); a spot light
// shines from `position` towards `target` within a circular cone of full
// angle `fov_deg`, and reaches nothing outside it.
#pragma once

#include <glm/vec3.hpp>

namespace zs {

enum class LightType { Directional, Spot };

struct Light {
  LightType type = LightType::Directional;
  glm::dvec3 direction{-1, -2, -1};  // directional
  glm::dvec3 position{0, 10, 0};     // spot
  glm::dvec3 target{0, 0, 0};        // spot
  double fov_deg = 60;               // spot: full cone angle, in (0, 170]
};

// Unit vector from world point p towards the light (directional: −direction).
glm::dvec3 to_light(const Light& l, const glm::dvec3& p);

// Whether p is inside a spot light's cone (always true for a directional
// light). A point at the light's position is outside.
bool in_light_cone(const Light& l, const glm::dvec3& p);

}  // namespace zs
