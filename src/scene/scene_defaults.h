// What a scene gets when it does not say: a camera framing the data and a
// transfer function over its scalar range. Low enough for every renderer and
// tool (no scene parsing here: scene.h is above the renderers).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/tets/tet_mesh.h"
#include "base/optics/transfer_function.h"
#include "base/view/camera.h"

namespace zs {

// Camera looking at the bounds from +z (view direction -z), y up, so that the
// whole box fits with a small margin. Throws std::runtime_error for extents
// the view cannot resolve.
Camera frame_bounds(const Bounds& b, Projection projection, uint32_t width, uint32_t height);
// frame_bounds of the mesh's bounds.
Camera auto_camera(const TetMesh& m, Projection projection, uint32_t width, uint32_t height);
// Ramp over the finite range of `scalars`: blue→white→red colour, opacity
// 0→0.6, with the given unit distance.
TransferFunction default_transfer_function(const std::vector<double>& scalars, double unit_distance);
// The ramp over the mesh's scalars, unit distance = bounding diagonal / 50.
TransferFunction default_transfer_function(const TetMesh& m);

}  // namespace zs
