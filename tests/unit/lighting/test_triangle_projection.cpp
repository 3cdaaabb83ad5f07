// Triangle projection (src/lighting/triangle_projection.h): back-face and
// view culling counts of a closed mesh.
#include <gtest/gtest.h>

#include "lighting/triangle_projection.h"
#include "support/test_surface_meshes.h"

namespace zs {
namespace {

// A convex closed mesh in a generic view: half its triangles face away.
TEST(Surfaces, BackFaceAndViewCullingCounts) {
  const TriangleMesh m = test::cube();
  Camera cam = test::perspective_camera({3.1, 2.3, 4.2}, {0.5, 0.5, 0.5}, 40);
  ProjectedTriangles pt;
  ProjectCounts c;
  project_triangles(m, View(cam, 64, 64), {true, true, 1e-6}, &pt, &c);
  EXPECT_EQ(c.triangles, 12u);
  EXPECT_EQ(c.back_culled, 6u);
  EXPECT_EQ(c.view_culled, 0u);
  EXPECT_EQ(pt.corners.size(), 6u);
  // Looking away: every front face is outside the view.
  cam.target = cam.eye + (cam.eye - cam.target);
  ProjectCounts c2;
  project_triangles(m, View(cam, 64, 64), {true, true, 1e-6}, &pt, &c2);
  EXPECT_EQ(c2.view_culled + c2.back_culled, 12u);
  EXPECT_EQ(pt.corners.size(), 0u);
}

}  // namespace
}  // namespace zs
