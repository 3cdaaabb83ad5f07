// Triangles of a surface mesh projected into a view (the camera's or a
// light's): screen vertices, the triangles to scan, and what was culled.
// Only geometry at view depth >= z_near is kept: triangles reaching behind
// the near plane are clipped in camera space (raster/triangle_clip.h); a cut
// point gets one id per mesh edge so clipped neighbours stay watertight.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/screen_triangle.h"
#include "geometry/triangles/triangle_mesh.h"
#include "base/view/camera.h"

namespace zs {

struct ProjectOptions {
  bool cull_back = true;   // drop one-sided triangles whose back faces the eye (TriangleMesh::two_sided)
  bool cull_view = true;   // drop triangles with no pixel centre of the image in their box
  double z_near = 0;       // keep view depth >= z_near
  const std::vector<uint8_t>* skip = nullptr;  // per triangle: nonzero = leave out (counted as skipped)
};

struct ProjectCounts {
  uint64_t triangles = 0;     // in the mesh
  uint64_t back_culled = 0;   // facing away (cull_back)
  uint64_t back_two_sided = 0;  // facing away but kept: two-sided (an open surface's other side)
  uint64_t view_culled = 0;   // outside the view volume: beside the image or behind z_near
  uint64_t near_clipped = 0;  // cut by the near plane (kept in part)
  uint64_t degenerate = 0;    // zero area or a non-finite point: nothing to draw
  uint64_t skipped = 0;       // left out by ProjectOptions::skip
  void operator+=(const ProjectCounts& o) {
    skipped += o.skipped;
    triangles += o.triangles;
    back_culled += o.back_culled;
    back_two_sided += o.back_two_sided;
    view_culled += o.view_culled;
    near_clipped += o.near_clipped;
    degenerate += o.degenerate;
  }
};

struct ProjectedTriangles {
  std::vector<ScreenVertex> verts;                // the mesh's points, then cut points
  std::vector<std::array<uint32_t, 3>> corners;   // into verts, front-facing order kept
  std::vector<uint32_t> source;                   // mesh triangle of each
  bool perspective = false;
};

void project_triangles(const TriangleMesh& m, const View& view, const ProjectOptions& opt, ProjectedTriangles* out,
                       ProjectCounts* counts);

// Whether a triangle's screen corners face the viewer: counter-clockwise in
// the world seen from the eye is clockwise on screen (rows grow downwards).
inline bool front_facing(const ScreenVertex v[3]) { return screen_det(v) < 0; }

}  // namespace zs
