#include "lighting/map_lookup.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include <glm/geometric.hpp>

namespace zs {

MapLookup map_lookup(const View& view, const ShadowMap& map, std::vector<double> face_bias) {
  const glm::dvec3 E = view.eye(), F = view.forward(), R = view.right(), U = view.up();
  const AffineLookup A = map.affine_lookup();
  const glm::dvec3 q[3] = {A.x, A.y, A.z};
  const double q0[3] = {A.x0, A.y0, A.z0};
  MapLookup M;
  for (int k = 0; k < 3; ++k) {
    M.e[k] = q0[k] + glm::dot(q[k], E);
    M.f[k] = glm::dot(q[k], F), M.r[k] = glm::dot(q[k], R), M.u[k] = glm::dot(q[k], U);
  }
  M.face_bias = std::move(face_bias);
  return M;
}

namespace {
// One of a lookup's column, row or light depth (constants e, f, r, u of
// MapLookup) for a pixel at (a, b) and depth s: map_inputs and map_range
// evaluate the same expression, so the range bounds the pixels' values.
template <bool perspective>
inline double map_coord(double e, double f, double r, double u, double a, double b, double s) {
  return perspective ? e + s * ((f + a * r) + b * u) : ((e + a * r) + b * u) + s * f;
}
}  // namespace

void map_range(const MapLookup& M, bool perspective, double a0, double a1, double cb, double s0, double s1, double* x,
               double* y, double* z) {
  double* out[3] = {x, y, z};
  for (int k = 0; k < 3; ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (double a : {a0, a1})
      for (double s : {s0, s1}) {
        const double v = perspective ? map_coord<true>(M.e[k], M.f[k], M.r[k], M.u[k], a, cb, s)
                                     : map_coord<false>(M.e[k], M.f[k], M.r[k], M.u[k], a, cb, s);
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
    out[k][0] = lo, out[k][1] = hi;
  }
}

void map_inputs(const MapLookup& M, bool perspective, int n, const double* __restrict ca, double cb,
                const double* __restrict depth, const uint32_t* __restrict face,
                double* __restrict X, double* __restrict Y, double* __restrict lim) {
  const double* __restrict fb = M.face_bias.data();
  const double e0 = M.e[0], e1 = M.e[1], e2 = M.e[2], f0 = M.f[0], f1 = M.f[1], f2 = M.f[2];
  const double r0 = M.r[0], r1 = M.r[1], r2 = M.r[2], u0 = M.u[0], u1 = M.u[1], u2 = M.u[2];
  auto run = [&](auto persp) {
    constexpr bool P = decltype(persp)::value;
    for (int i = 0; i < n; ++i) {
      const double a = ca[i], s = depth[i];
      X[i] = map_coord<P>(e0, f0, r0, u0, a, cb, s);
      Y[i] = map_coord<P>(e1, f1, r1, u1, a, cb, s);
      const double z = map_coord<P>(e2, f2, r2, u2, a, cb, s);
      lim[i] = z - (fb[face[i]] + std::abs(z) * 0x1p-20);  // shadow_map.h's bias_total
    }
  };
  if (perspective)
    run(std::true_type{});
  else
    run(std::false_type{});
}

}  // namespace zs
