// Only geometry at positive distance along a ray is rendered (scene spec).
// Where the near plane z = z_near cuts the visible mesh — the eye inside the
// mesh, or an orthographic eye plane through it — two things are needed:
//   * faces reaching behind the plane are clipped to their part in front;
//   * each visible tet cut by the plane contributes its cross-section as an
//     entry face at z_near, so rays that start inside a tet integrate from
//     the plane on.
// New vertices sit on mesh edges; each gets one id per edge, so the clipped
// faces and cross-sections meet watertight (screen_triangle.h tie rule).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "raster/screen_triangle.h"
#include "base/view/camera.h"
#include "render/volume/face_classes.h"

namespace zs {

struct NearTriangle {
  ScreenVertex v[3];
  FaceClass cls;  // Entry for cross-sections; the face's class for clipped faces
};

// Appends the near-plane triangles; marks the clipped faces in `clipped`
// (one byte per face). `sv` holds every mesh vertex in view space.
void clip_at_near_plane(const TetMesh& m, const Topology& topo, const View& view,
                        const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                        const std::vector<uint8_t>& tet_visible, double z_near, std::vector<NearTriangle>* out,
                        std::vector<uint8_t>* clipped);

}  // namespace zs
