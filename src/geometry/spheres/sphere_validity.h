// The rules every sphere reader applies to one record, so the text and the
// binary forms accept, skip and reject the same spheres.
#pragma once

#include <cmath>

namespace zs {

// A sphere that can be drawn: finite centre, finite radius > 0. The readers
// skip the others and count them (SphereSet::invalid).
inline bool drawable_sphere(double x, double y, double z, double r) {
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z) && std::isfinite(r) && r > 0.0;
}

// A colour or opacity component the readers accept: finite, in [0, 1].
inline bool valid_rgba_component(double v) { return v >= 0.0 && v <= 1.0; }  // false for NaN

}  // namespace zs
