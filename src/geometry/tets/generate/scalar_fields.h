// Per-point scalar fields to attach to generated meshes. Each sets
// m.scalars and m.scalar_name. Analytic fields take explicit parameters (for
// tests); apply_field() picks defaults scaled to the mesh bounds (for the CLI).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/tets/generate/voxel_image.h"
#include "geometry/tets/tet_mesh.h"

namespace zs {

// (p[axis] - lo) / (hi - lo): 0 at lo, 1 at hi.
void field_linear(TetMesh& m, int axis, double lo, double hi);
// |p - centre| / scale.
void field_radial(TetMesh& m, const glm::dvec3& centre, double scale);

struct Gaussian {
  glm::dvec3 centre;
  double sigma;
  double amplitude;
};
// sum_k amplitude_k * exp(-|p - c_k|^2 / (2 sigma_k^2)).
void field_gaussians(TetMesh& m, const std::vector<Gaussian>& gs);
// `count` Gaussians inside the bounds, deterministic per seed.
std::vector<Gaussian> random_gaussians(const Bounds& b, int count, uint64_t seed);

// prod_axis sin(2 pi freq (p - lo) / (hi - lo)).
void field_sin(TetMesh& m, const Bounds& b, double freq);

// Euclidean distance from each point to the mesh boundary (faces used by one
// tet), through a CGAL AABB tree. 0 on the boundary.
void field_distance(TetMesh& m);

// Trilinear samples of the image at each point.
void field_image(TetMesh& m, const VoxelImage& img);

// Field names the CLI accepts (the image field needs `img`).
const std::vector<std::string>& field_names();
// Throws std::invalid_argument for an unknown name or "image" without an image.
void apply_field(TetMesh& m, const std::string& name, uint64_t seed, const VoxelImage* img = nullptr);

}  // namespace zs
