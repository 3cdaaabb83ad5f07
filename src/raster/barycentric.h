// Per-pixel barycentric weights of a screen triangle, perspective-correct
// when the projection is: any per-vertex attribute (normal, uv, colour)
// interpolates as Σ w_k·attr_k.
//
// The screen weights λ_k are affine in (X, Y). Perspective, attributes are
// affine in camera space, so λ_k/z_k is what is affine on screen:
// w_k = (λ_k/z_k) / Σ_j (λ_j/z_j). Evaluated relative to vertex 0 (no
// cancellation against far-away origins), with w0 = 1 − w1 − w2 so the
// weights sum to 1 and vertex 0 gets exactly (1, 0, 0).
#pragma once

#include "raster/screen_triangle.h"

namespace zs {

struct Barycentric {
  double x0, y0;            // vertex 0
  double g1x, g1y, g2x, g2y;  // λ1, λ2 = g·(X − x0, Y − y0)
  double iz0, d1, d2;       // perspective: 1/z0, 1/z1 − 1/z0, 1/z2 − 1/z0
  double iz1, iz2;          // perspective: 1/z1, 1/z2
  bool perspective;

  void weights(double X, double Y, double w[3]) const {
    const double dx = X - x0, dy = Y - y0;
    double l1 = g1x * dx + g1y * dy, l2 = g2x * dx + g2y * dy;
    if (perspective) {
      const double inv = 1.0 / (iz0 + l1 * d1 + l2 * d2);  // 1 / interpolated 1/z
      l1 = l1 * iz1 * inv;
      l2 = l2 * iz2 * inv;
    }
    w[0] = 1.0 - l1 - l2;
    w[1] = l1;
    w[2] = l2;
  }
};

// Set up from the three screen vertices (x, y pixel coordinates, z view
// depth; perspective needs z > 0). False for a zero-area (or non-finite)
// triangle.
bool setup_barycentric(const ScreenVertex v[3], bool perspective, Barycentric* b);

}  // namespace zs
