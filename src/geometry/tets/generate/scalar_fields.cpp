#include "geometry/tets/generate/scalar_fields.h"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace zs {

// Each point's value on its own, so the parallel loop gives the serial
// loop's doubles bit for bit (the build never contracts to FMA) at 100 M
// points in a second or two (issue 41).
template <class F>
static void fill(TetMesh& m, const char* name, F&& f) {
  m.scalars.resize(m.points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, m.points.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) m.scalars[i] = f(m.points[i]);
  });
  m.scalar_name = name;
}

void field_linear(TetMesh& m, int axis, double lo, double hi) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("axis must be 0, 1 or 2");
  const double span = hi > lo ? hi - lo : 1.0;
  fill(m, "linear", [&](const glm::dvec3& p) { return (p[axis] - lo) / span; });
}

void field_radial(TetMesh& m, const glm::dvec3& centre, double scale) {
  const double s = scale > 0 ? scale : 1.0;
  fill(m, "radial", [&](const glm::dvec3& p) { return glm::length(p - centre) / s; });
}

void field_gaussians(TetMesh& m, const std::vector<Gaussian>& gs) {
  fill(m, "gaussians", [&](const glm::dvec3& p) {
    double v = 0;
    for (const Gaussian& g : gs) {
      glm::dvec3 d = p - g.centre;
      v += g.amplitude * std::exp(-glm::dot(d, d) / (2 * g.sigma * g.sigma));
    }
    return v;
  });
}

std::vector<Gaussian> random_gaussians(const Bounds& b, int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double diag = b.diagonal() > 0 ? b.diagonal() : 1.0;
  std::vector<Gaussian> gs;
  for (int k = 0; k < count; ++k) {
    glm::dvec3 c = b.lo + (b.hi - b.lo) * glm::dvec3(u(rng), u(rng), u(rng));
    gs.push_back({c, diag * (0.08 + 0.12 * u(rng)), 0.5 + 0.5 * u(rng)});
  }
  return gs;
}

void field_sin(TetMesh& m, const Bounds& b, double freq) {
  const glm::dvec3 span = glm::max(b.hi - b.lo, glm::dvec3(1e-300));
  const double w = 2 * std::numbers::pi * freq;
  fill(m, "sin", [&](const glm::dvec3& p) {
    glm::dvec3 t = (p - b.lo) / span;
    return std::sin(w * t.x) * std::sin(w * t.y) * std::sin(w * t.z);
  });
}

void field_image(TetMesh& m, const VoxelImage& img) {
  fill(m, "image", [&](const glm::dvec3& p) { return img.sample(p); });
}

const std::vector<std::string>& field_names() {
  static const std::vector<std::string> n = {"radial", "linear", "gaussians", "sin", "distance", "image"};
  return n;
}

void apply_field(TetMesh& m, const std::string& name, uint64_t seed, const VoxelImage* img) {
  const Bounds b = bounds_of(m);
  if (name == "linear") {
    field_linear(m, 0, b.lo.x, b.hi.x);
  } else if (name == "radial") {
    field_radial(m, (b.lo + b.hi) * 0.5, b.diagonal() * 0.5);
  } else if (name == "gaussians") {
    field_gaussians(m, random_gaussians(b, 4, seed));
  } else if (name == "sin") {
    field_sin(m, b, 1.5);
  } else if (name == "distance") {
    field_distance(m);
  } else if (name == "image") {
    if (!img) throw std::invalid_argument("the image field needs a source image (mesh generate image)");
    field_image(m, *img);
  } else {
    throw std::invalid_argument("unknown field '" + name +
                                "' (expected radial, linear, gaussians, sin, distance or image)");
  }
}

}  // namespace zs
