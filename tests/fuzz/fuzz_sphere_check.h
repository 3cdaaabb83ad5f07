// What every sphere set a reader accepts must satisfy (sphere_set.h and the
// readers' contracts); a violation aborts, which libFuzzer reports.
#pragma once

#include <cmath>
#include <cstdlib>

#include "spheres/sphere_set.h"

namespace zs::fuzz {

inline void check_spheres(const SphereSet& s) {
  if (s.size() == 0 || s.radii.size() != s.size()) std::abort();
  if (s.has_scalars() && s.scalars.size() != s.size()) std::abort();
  if (s.has_rgba() && s.rgba.size() != s.size()) std::abort();
  if (s.has_elements() && s.element.size() != s.size()) std::abort();
  for (size_t i = 0; i < s.size(); ++i) {
    const glm::dvec3& c = s.centres[i];
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) std::abort();
    if (!(s.radii[i] > 0.0) || !std::isfinite(s.radii[i])) std::abort();  // invalid ones are skipped
    if (s.has_rgba())
      for (int k = 0; k < 4; ++k)
        if (!(s.rgba[i][k] >= 0.f && s.rgba[i][k] <= 1.f)) std::abort();
  }
  if (s.degenerate > s.size()) std::abort();
}

}  // namespace zs::fuzz
