// A 3D grey-level image (.inr and the other formats CGAL's ImageIO reads),
// kept as floats for sampling scalar fields on generated meshes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace CGAL {
class Image_3;
}

namespace zs {

struct VoxelImage {
  size_t nx = 0, ny = 0, nz = 0;
  glm::dvec3 spacing{1.0}, origin{0.0};  // voxel (i,j,k) sits at origin + (i,j,k)*spacing
  std::vector<float> values;             // x fastest

  float at(size_t i, size_t j, size_t k) const { return values[(k * ny + j) * nx + i]; }
  // Trilinear interpolation in world coordinates; points outside the grid
  // take the value at the nearest grid point (clamped).
  double sample(const glm::dvec3& p) const;
};

// Throws zs::FileError naming the file.
VoxelImage read_voxel_image(const std::string& path);
// The values of an image already read (`path` names it in errors).
VoxelImage voxel_image_from(const CGAL::Image_3& img, const std::string& path);

}  // namespace zs
