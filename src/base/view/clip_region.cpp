#include "base/view/clip_region.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

void ClipRegion::add_box(const glm::dvec3& lo, const glm::dvec3& hi) {
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 n(0.0);
    n[a] = -1;
    planes.push_back({n, lo[a]});  // x_a >= lo_a
    n[a] = 1;
    planes.push_back({n, -hi[a]});  // x_a <= hi_a
  }
}

bool ClipRegion::interval(const glm::dvec3& p, const glm::dvec3& w, double* t0, double* t1) const {
  *t0 = -INFINITY, *t1 = INFINITY;
  for (const ClipPlane& c : planes) {
    // n·(p + t w) + d = a + t·b <= 0.
    const double a = glm::dot(c.n, p) + c.d, b = glm::dot(c.n, w);
    if (b > 0) {
      *t1 = std::fmin(*t1, -a / b);
    } else if (b < 0) {
      *t0 = std::fmax(*t0, -a / b);
    } else if (!(a <= 0)) {  // parallel to the plane and outside it
      *t0 = INFINITY, *t1 = -INFINITY;
      return false;
    }
  }
  return *t0 <= *t1;
}

bool ClipRegion::excludes(const glm::dvec3* pts, int n) const {
  for (const ClipPlane& c : planes) {
    bool all_out = true;
    for (int k = 0; k < n && all_out; ++k) all_out = glm::dot(c.n, pts[k]) + c.d >= 0;
    if (all_out) return true;
  }
  return false;
}

}  // namespace zs
