// How a surface point is lit (the scene's `shading` block for surfaces;
// docs/shadows.md): Blinn–Phong with several lights, each term scaled by the
// fraction of that light reaching the point (the shadow test's `lit`):
//   c = base·(ambient + Σ_l lit_l·diffuse·max(0, N·L_l)) + Σ_l lit_l·specular·max(0, N·H_l)^shininess
// (white highlights), each channel clamped to [0, 1]. `phong` interpolates
// the points' normals over the triangle; `flat` uses the face normal.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "lighting/shading_model.h"  // shininess_power, ShadingModel

namespace zs {

struct SurfaceShading {
  ShadingModel model = ShadingModel::Phong;  // Flat: the face normal (still lit)
  double ambient = 0.2, diffuse = 0.7, specular = 0.3, shininess = 32;
};

// Adds one light's diffuse and specular terms: `n` unit normal facing the
// viewer, `l` unit vector towards the light, `v` unit vector towards the eye.
inline void add_light(const SurfaceShading& sh, const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v,
                      double lit, double* diffuse, double* specular) {
  if (!(lit > 0)) return;
  const double nl = glm::dot(n, l);
  if (!(nl > 0)) return;
  *diffuse += lit * sh.diffuse * nl;
  const glm::dvec3 h = glm::normalize(l + v);
  const double nh = glm::dot(n, h);
  if (nh > 0 && sh.specular > 0) *specular += lit * sh.specular * shininess_power(nh, sh.shininess);
}

inline glm::dvec3 surface_colour(const SurfaceShading& sh, const glm::dvec3& base, double diffuse, double specular) {
  glm::dvec3 c = base * (sh.ambient + diffuse) + glm::dvec3(specular);
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(c[k], 0.0, 1.0);
  return c;
}

}  // namespace zs
