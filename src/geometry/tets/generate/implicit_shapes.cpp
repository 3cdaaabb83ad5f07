#include "geometry/tets/generate/implicit_shapes.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

namespace {

double sphere(const glm::dvec3& p) { return glm::length(p) - 1.0; }

double torus(const glm::dvec3& p) {
  const double R = 1.0, r = 0.4;
  double q = std::sqrt(p.x * p.x + p.y * p.y) - R;
  return std::sqrt(q * q + p.z * p.z) - r;
}

// Union of overlapping balls pierced by three tunnels (one per axis): a
// non-convex solid with holes through it. Distances keep the gradient ~1,
// which Mesh_3's surface oracle likes.
double balls(const glm::dvec3& p) {
  static const glm::dvec3 c[] = {{0, 0, 0}, {0.7, 0, 0}, {-0.7, 0, 0}, {0, 0.6, 0.2}, {0, -0.6, -0.2}};
  static const double r[] = {0.75, 0.5, 0.5, 0.45, 0.45};
  double d = 1e300;
  for (int i = 0; i < 5; ++i) d = std::min(d, glm::length(p - c[i]) - r[i]);
  const double rt = 0.18;
  double tx = std::hypot(p.y, p.z) - rt;        // along x
  double ty = std::hypot(p.x - 0.35, p.z) - rt; // along y, off-centre
  double tz = std::hypot(p.x + 0.35, p.y) - rt; // along z, off-centre
  return std::max(d, -std::min({tx, ty, tz}));
}

double ellipsoid(const glm::dvec3& p) {
  // Scaled-sphere distance: exact on the surface, approximate elsewhere.
  glm::dvec3 q = p / glm::dvec3(1.0, 0.6, 0.4);
  return (glm::length(q) - 1.0) * 0.4;
}

}  // namespace

const std::vector<ImplicitShape>& implicit_catalog() {
  static const std::vector<ImplicitShape> cat = {
      {"sphere", "unit sphere", sphere, 2.0},
      {"torus", "torus R=1 r=0.4", torus, 2.0},
      {"balls", "union of balls pierced by three tunnels", balls, 2.0},
      {"ellipsoid", "ellipsoid with radii 1, 0.6, 0.4", ellipsoid, 2.0},
  };
  return cat;
}

const ImplicitShape* find_implicit(const std::string& name) {
  for (const ImplicitShape& s : implicit_catalog())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace zs
