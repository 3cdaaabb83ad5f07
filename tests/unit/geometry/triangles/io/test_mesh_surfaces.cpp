// Surfaces made of a tet mesh (mesh_surfaces.h): the boundary has one
// triangle per boundary face, every one on the box's sides; an isosurface of a
// linear field is the plane where it takes the value; cell data are
// contoured once averaged onto the points; nothing to draw is one line.
#include <cmath>

#include <gtest/gtest.h>

#include "base/util/file_error.h"
#include "geometry/tets/topology.h"
#include "geometry/triangles/io/mesh_surfaces.h"
#include "support/test_meshes.h"

namespace zs {
namespace {

const glm::dvec3 kLo{-1.0, -0.7, -0.5}, kHi{1.0, 0.7, 0.5};

TEST(MeshSurfaces, BoundaryIsTheBoundaryFaces) {
  const TetMesh m = test::box_mesh({4, 3, 2}, kLo, kHi, [](const glm::dvec3& p) { return p.x; });
  const TriangleMesh b = boundary_surface(m, "box");
  EXPECT_EQ(b.num_tris(), build_topology(m).num_boundary_faces);
  for (const auto& t : b.tris)
    for (uint32_t v : t) {
      const glm::dvec3& p = b.points[v];
      const bool on_side = p.x == kLo.x || p.x == kHi.x || p.y == kLo.y || p.y == kHi.y || p.z == kLo.z || p.z == kHi.z;
      ASSERT_TRUE(on_side) << p.x << " " << p.y << " " << p.z;
    }
}

TEST(MeshSurfaces, IsosurfaceOfALinearFieldIsItsPlane) {
  TetMesh m = test::box_mesh({4, 3, 2}, kLo, kHi, [](const glm::dvec3& p) { return 2 * p.x + p.y; });
  const TriangleMesh iso = isosurfaces(m, {0.3, -1.1}, "box");
  ASSERT_GT(iso.num_tris(), 10u);
  double area = 0;
  for (const auto& t : iso.tris) {
    for (uint32_t v : t) {
      const double f = 2 * iso.points[v].x + iso.points[v].y;
      ASSERT_TRUE(std::abs(f - 0.3) < 1e-9 || std::abs(f + 1.1) < 1e-9) << f;
    }
    area += 0.5 * glm::length(glm::cross(iso.points[t[1]] - iso.points[t[0]], iso.points[t[2]] - iso.points[t[0]]));
  }
  // Both planes cross the whole box: each a parallelogram of depth 1 (z) and
  // length 1.4·sqrt(1 + 1/4) (2x + y = c over y in [-0.7, 0.7]).
  EXPECT_NEAR(area, 2 * 1.4 * std::sqrt(1.25), 1e-9);
  // Cell data: contoured on the points' averages.
  m.cell_scalars.clear();
  for (const Tet& t : m.tets) m.cell_scalars.push_back(m.points[t[0]].x);
  m.scalars.clear();
  EXPECT_GT(isosurfaces(m, {0.0}, "box").num_tris(), 0u);
}

TEST(MeshSurfaces, NothingToDrawIsAnError) {
  TetMesh m = test::box_mesh({2, 2, 2}, kLo, kHi, [](const glm::dvec3& p) { return p.x; });
  try {
    isosurfaces(m, {5.0}, "box.vtu");
    ADD_FAILURE() << "no error for a value outside the scalar's range";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("box.vtu", 0), 0u) << e.what();
  }
  m.scalars.clear();
  EXPECT_THROW(isosurfaces(m, {0.0}, "box.vtu"), FileError);
}

}  // namespace
}  // namespace zs
