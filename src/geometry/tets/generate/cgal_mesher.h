// CGAL Mesh_3: implicit solids and grey-level 3D images to tet meshes. All of
// Mesh_3 is instantiated in cgal_mesher.cpp alone (it compiles slowly).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "geometry/tets/generate/implicit_shapes.h"
#include "geometry/tets/tet_mesh.h"

namespace zs {

struct Mesh3Criteria {
  double facet_angle = 30;        // degrees, lower bound
  double facet_size = 0.1;        // surface Delaunay ball radius bound
  double facet_distance = 0.025;  // surface approximation error bound
  double cell_radius_edge = 2.0;  // tet radius-edge ratio bound
  double cell_size = 0.1;         // tet circumradius bound
  uint64_t seed = 1;              // Mesh_3's random choices
  size_t max_points = 250000;     // refused up front when the sizes need more; refinement stops there

  // One-knob defaults: sizes equal to `size`, distance a quarter of it.
  static Mesh3Criteria from_size(double size) {
    Mesh3Criteria c;
    c.facet_size = c.cell_size = size;
    c.facet_distance = size / 4;
    return c;
  }
};

// Both are deterministic for given criteria (seed included): Mesh_3's
// sliver perturbation and exudation run to their bounds instead of to a
// time limit. Both stop with an error rather than run without bound: sizes
// that need more than max_points points are refused before meshing (from
// the solid's volume), and refinement that reaches max_points throws.

// Throws std::invalid_argument on bad criteria, std::runtime_error when
// the point limit is reached.
TetMesh mesh_implicit(const ImplicitShape& shape, const Mesh3Criteria& crit);

// Meshes where the image value is above `iso` (or below, if !inside_above)
// after CGAL's trilinear interpolation; the surface is found from the voxel
// grid (iso_region.h). Throws zs::FileError naming the file, also when the
// iso-value selects no voxel or every voxel.
TetMesh mesh_gray_image(const std::string& path, double iso, bool inside_above,
                        const Mesh3Criteria& crit);

}  // namespace zs
