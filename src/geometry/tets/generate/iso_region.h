// What an iso-value selects in a grey-level image, worked out before CGAL
// Mesh_3 runs: Mesh_3 looks for the surface by shooting random rays until
// it has hit it, forever when the region is empty (and for hours when it is
// tiny), so the region is checked here and its surface points are found on
// the voxel grid instead.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/tets/generate/voxel_image.h"

namespace zs {

struct IsoRegion {
  float lo = 0, hi = 0;  // the image's value range
  double volume = 0;     // voxels on the meshed side times the voxel volume
  // Grid edges (world coordinates, inside end first) that the iso-surface
  // crosses, evenly spread over all of them in scan order.
  std::vector<std::array<glm::dvec3, 2>> crossings;
};

// Grid point (i, j, k) counts as inside when its value is above `iso`
// (below, if !above) and it lies where CGAL interpolates the image (index
// below n - 1 on each axis; elsewhere is outside, closing the solid at the
// border). Throws std::invalid_argument naming the value range when the
// iso-value selects no voxel, every voxel, or no grid edge crosses it.
IsoRegion find_iso_region(const VoxelImage& img, double iso, bool above, size_t max_crossings);

}  // namespace zs
