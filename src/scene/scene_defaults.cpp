#include "scene/scene_defaults.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace zs {

Camera frame_bounds(const Bounds& b, Projection projection, uint32_t width, uint32_t height) {
  Camera cam;
  cam.projection = projection;
  const glm::dvec3 c = b.centre();
  const double r = b.empty ? 1.0 : std::max(b.half_diagonal(), 1e-300);
  if (!b.empty && b.half_diagonal() == 0) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "all points coincide (at %.9g, %.9g, %.9g): nothing has an extent for the "
                  "automatic camera to frame; give a camera", b.lo.x, b.lo.y, b.lo.z);
    throw std::runtime_error(msg);
  }
  // The view's basis and depths square lengths of this order: beyond these
  // they under- or overflow and every depth would be lost.
  if (!b.empty && (r < 1e-140 || r > 1e140 || glm::length(c) > 1e140)) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "extent %.3g (centre at distance %.3g) is outside what the automatic camera "
                  "frames (1e-140 to 1e140); give a camera or rescale the data", 2 * r, glm::length(c));
    throw std::runtime_error(msg);
  }
  const double aspect = double(width) / double(height);
  cam.target = c;
  cam.up = {0, 1, 0};
  cam.height = 2.2 * r / std::min(1.0, aspect);
  cam.fov_y = 30.0;
  // Far enough that the bounding sphere fits the vertical (and horizontal) fov.
  const double half = std::atan(std::tan(cam.fov_y * M_PI / 360.0) * std::min(1.0, aspect));
  cam.eye = c + glm::dvec3(0, 0, 1.1 * r / std::sin(half));
  return cam;
}

Camera auto_camera(const TetMesh& m, Projection projection, uint32_t width, uint32_t height) {
  return frame_bounds(bounds_of(m), projection, width, height);
}

TransferFunction default_transfer_function(const std::vector<double>& scalars, double unit) {
  double lo = INFINITY, hi = -INFINITY;
  for (double s : scalars)
    if (std::isfinite(s)) lo = std::min(lo, s), hi = std::max(hi, s);
  if (!(lo < hi) || !std::isfinite(4.0 / (hi - lo))) {
    // Constant (or no finite) scalars, or a range too narrow for the ramp's
    // interpolation (subnormal widths): a ramp centred on the value, wide
    // enough to be representable next to it, so the mesh shows mid-ramp.
    const double v = std::isfinite(lo) ? lo : 0.0;
    const double d = std::max(1.0, std::abs(v) * 1e-6);
    lo = v - d, hi = v + d;
    if (!std::isfinite(hi)) lo = v - 2 * d, hi = v;  // only next to the largest doubles
    if (!std::isfinite(lo)) lo = v, hi = v + 2 * d;
  }
  const double mid = 0.5 * lo + 0.5 * hi;  // (lo + hi) / 2 overflows for scalars near the largest double
  return TransferFunction({{lo, 0.23, 0.30, 0.75}, {mid, 0.87, 0.87, 0.87}, {hi, 0.71, 0.02, 0.15}},
                          {{lo, 0.0}, {hi, 0.6}}, unit);
}

TransferFunction default_transfer_function(const TetMesh& m) {
  // Unit distance: bounding diagonal / 50, from the half so it stays finite.
  return default_transfer_function(m.scalar_values(), std::max(bounds_of(m).half_diagonal() / 25.0, 1e-300));
}

}  // namespace zs
