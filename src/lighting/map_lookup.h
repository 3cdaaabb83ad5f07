// A directional shadow map's lookup as functions of a pixel's camera-plane
// coordinates (a, b) and view depth s, so a pixel needs no world point
// (docs/shadows.md, "Directional lookups without a world point"): with
// p = E + s·w, w = F + a·R + b·U (perspective) or p = E + a·R + b·U + s·F,
// an affine Q(p) (ShadowMap::affine_lookup) is QE + s·(QF + a·QR + b·QU) or
// QE + a·QR + b·QU + s·QF. The bias's normal part is per face (its normal
// against the light: ShadowMap::face_bias), worked out once by the caller.
#pragma once

#include <cstdint>
#include <vector>

#include "lighting/shadow_map.h"
#include "base/view/camera.h"

namespace zs {

struct MapLookup {
  double e[3], f[3], r[3], u[3];  // QE, QF, QR, QU for Q = map column X, row Y, light depth z
  std::vector<double> face_bias;  // per face; NaN: turned from the light
};
MapLookup map_lookup(const View& view, const ShadowMap& map, std::vector<double> face_bias);

// Bounds on map_inputs' X, Y and light depth z over pixels with a between
// a0 and a1 and depth s in [s0, s1]: each is bilinear (perspective) or affine
// (orthographic) in (a, s), so its extremes are at the four corners. Out:
// x[0..1], y[0..1], z[0..1] (low, high), before any rounding margin.
void map_range(const MapLookup& M, bool perspective, double a0, double a1, double cb, double s0, double s1, double* x,
               double* y, double* z);

// The map column X, row Y and test limit lim = z − bias_total (shadow_map.h)
// of n pixels on faces `face`, for ShadowMap::counts_at.
void map_inputs(const MapLookup& M, bool perspective, int n, const double* __restrict ca, double cb,
                const double* __restrict depth, const uint32_t* __restrict face,
                double* __restrict X, double* __restrict Y, double* __restrict lim);

}  // namespace zs
