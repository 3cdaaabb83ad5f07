// C2 of the sphere test sets (test_sets.h): maximal balls of the pore space
// of a real thresholded 3D image, CGAL's demo skull (skull_2.9.inr in
// Debian's libcgal-demo data.tar.gz; 64^3 floats). The only sphere code that
// links VTK (its Euclidean distance transform and image resize).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "geometry/spheres/sphere_set.h"

namespace zs {

struct PoreBallsInfo {
  int upsample = 0;          // the image was resized to (64 upsample)^3
  size_t maximal_balls = 0;  // found at that size, before keeping `count`
};

// Resizes the image by an integer factor f (linear interpolation), calls
// voxels with a value below the threshold 2.9 (the skull surface's level:
// the image's name) pore and the rest solid, takes each pore voxel's
// Euclidean distance to the solid (vtkImageEuclideanDistance) and keeps a
// voxel as a maximal ball when no 26-neighbour's ball contains its ball
// (d(n) >= d(v) + |n - v|): a local test, the usual discrete medial axis.
// f is the smallest of 1, 2, ... 12 giving at least `count` balls; the
// `count` largest balls are kept (ties by voxel order). Centres and radii
// are in the image's world units (its anisotropic voxel size). Colour by
// radius (blue for small to orange for large); the largest 10% are fairly
// opaque (alpha 0.5-1), the rest highly translucent (alpha 0.02-0.15, the
// seed jitters it). Throws FileError naming the tarball and the package when
// it is absent, std::runtime_error when even f = 12 yields too few balls.
SphereSet generate_c2(size_t count, uint64_t seed, const std::string& tarball, PoreBallsInfo* info = nullptr);

}  // namespace zs
