// How a sphere's surface point is lit (the scene's `shading` block); shared by
// the sphere renderer and the Embree reference so both compute the same
// colour from the same hit.
//
// Vectors are in view space: x along the camera's right, y along its up, z
// towards the viewer (so the camera looks down −z). `light_direction` is the
// direction the light travels; the default (0, 0, −1) is a headlight.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace zs {

enum class ShadingModel { Phong, Flat };

struct Shading {
  ShadingModel model = ShadingModel::Phong;
  glm::dvec3 light_direction{0, 0, -1};
  double ambient = 0.2, diffuse = 0.7, specular = 0.3, shininess = 32;
};

// x^e for x in (0, 1]: by squaring when e is a whole number up to 4096 (the
// usual exponents; std::pow costs as much as the rest of a pixel's shading),
// else std::pow.
inline double shininess_power(double x, double e) {
  if (!(e >= 0 && e <= 4096 && e == std::floor(e))) return std::pow(x, e);
  double r = 1, b = x;
  for (unsigned n = unsigned(e); n; n >>= 1, b *= b)
    if (n & 1) r *= b;
  return r;
}

// Blinn–Phong: base·(ambient + diffuse·max(0, N·L)) + specular·max(0, N·H)^shininess
// (white highlight), L = −light_direction, H = normalize(L + V), each channel
// clamped to [0, 1]; flat: base unlit. `n`: unit normal facing the viewer;
// `v`: unit vector from the point towards the eye (both view space).
inline glm::dvec3 shade(const Shading& sh, const glm::dvec3& base, const glm::dvec3& n, const glm::dvec3& v) {
  if (sh.model == ShadingModel::Flat) return base;
  const glm::dvec3 l = -glm::normalize(sh.light_direction);
  const double nl = std::max(0.0, glm::dot(n, l));
  const glm::dvec3 h = glm::normalize(l + v);
  const double nh = std::max(0.0, glm::dot(n, h));
  const double spec = nh > 0 ? sh.specular * shininess_power(nh, sh.shininess) : 0.0;
  glm::dvec3 c = base * (sh.ambient + sh.diffuse * nl) + glm::dvec3(spec);
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(c[k], 0.0, 1.0);
  return c;
}

}  // namespace zs
