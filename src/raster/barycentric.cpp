#include "raster/barycentric.h"

#include <cmath>

namespace zs {

bool setup_barycentric(const ScreenVertex v[3], bool perspective, Barycentric* b) {
  const double ex1 = v[1].x - v[0].x, ey1 = v[1].y - v[0].y;
  const double ex2 = v[2].x - v[0].x, ey2 = v[2].y - v[0].y;
  const double det = ex1 * ey2 - ex2 * ey1;
  if (det == 0 || !std::isfinite(det)) return false;
  if (perspective && !(v[0].z > 0 && v[1].z > 0 && v[2].z > 0)) return false;
  const double inv = 1.0 / det;
  b->x0 = v[0].x;
  b->y0 = v[0].y;
  // Cramer's rule on (X − x0, Y − y0) = λ1·e1 + λ2·e2.
  b->g1x = ey2 * inv;
  b->g1y = -ex2 * inv;
  b->g2x = -ey1 * inv;
  b->g2y = ex1 * inv;
  b->perspective = perspective;
  b->iz0 = b->iz1 = b->iz2 = 1;
  b->d1 = b->d2 = 0;
  if (perspective) {
    b->iz0 = 1.0 / v[0].z;
    b->iz1 = 1.0 / v[1].z;
    b->iz2 = 1.0 / v[2].z;
    b->d1 = b->iz1 - b->iz0;
    b->d2 = b->iz2 - b->iz0;
  }
  return true;
}

}  // namespace zs
