// Mesh generators stop in bounded time or say why (empty or whole iso
// regions, sizes beyond the point/tet limits), give the same mesh for the
// same input and seed, and meet --tets within 10 %. Meshes are small.
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "geometry/tets/generate/cgal_mesher.h"
#include "geometry/tets/generate/iso_region.h"
#include "geometry/tets/generate/shape_mesher.h"
#include "geometry/tets/generate/shapes.h"
#include "geometry/tets/generate/tetgen_mesher.h"
#include "base/util/file_error.h"
#include "support/file_error_of.h"
#include "support/test_inr.h"
#include "support/test_paths.h"

namespace fs = std::filesystem;
using zs::test::thrown;

namespace {

// 16^3 voxels of size 0.5, value = distance to the centre (0.43 to 6.5).
std::string ball_image() {
  const fs::path p = zs::test::scratch_dir() / "bounds_ball.inr";
  const int n = 16;
  const double vx = 0.5, c = (n - 1) * vx / 2;
  std::vector<float> data;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) data.push_back(float(glm::length(glm::dvec3(i, j, k) * vx - glm::dvec3(c))));
  zs::test::write_inr(p, n, vx, data);
  return p.string();
}

bool same(const zs::TetMesh& a, const zs::TetMesh& b) {
  return a.points == b.points && a.tets == b.tets && a.scalars == b.scalars;
}

}  // namespace

// These ran forever: Mesh_3 shot random rays until one hit a surface.
TEST(GenerateBounds, IsoSelectingNothingOrEverythingNamesTheRange) {
  const std::string img = ball_image();
  const zs::Mesh3Criteria crit = zs::Mesh3Criteria::from_size(1.0);
  const std::string range = " (the image's values are 0.433013 to 6.49519)";
  auto msg = [&](double iso, bool above) {
    return thrown<zs::FileError>([&] { zs::mesh_gray_image(img, iso, above, crit); });
  };
  EXPECT_EQ(msg(1000, true), img + ": no voxel is above iso 1000" + range);
  EXPECT_EQ(msg(6.6, true), img + ": no voxel is above iso 6.6" + range);
  EXPECT_EQ(msg(-1, false), img + ": no voxel is below iso -1" + range);
  EXPECT_EQ(msg(0.1, true), img + ": every voxel is above iso 0.1" + range + ": the solid would be the whole image box");
  EXPECT_EQ(msg(7, false), img + ": every voxel is below iso 7" + range + ": the solid would be the whole image box");
  EXPECT_EQ(msg(NAN, true), img + ": iso value nan is not a finite number");
}

// The surface is seeded from voxel edges that cross it: a region a few
// voxels across (far too small for random rays to find often) still meshes.
TEST(GenerateBounds, SmallIsoRegionIsFoundOnTheGrid) {
  const std::string img = ball_image();
  zs::VoxelImage v = zs::read_voxel_image(img);
  zs::IsoRegion r = zs::find_iso_region(v, 1.0, /*above=*/false, 12);
  EXPECT_EQ(r.crossings.size(), 12u);
  for (const auto& e : r.crossings) {  // inside end first, one voxel apart
    EXPECT_LT(v.sample(e[0]), 1.0);
    EXPECT_GT(v.sample(e[1]), 1.0);
    EXPECT_NEAR(glm::length(e[1] - e[0]), 0.5, 1e-12);
  }
  zs::TetMesh m = zs::mesh_gray_image(img, 1.0, false, zs::Mesh3Criteria::from_size(0.3));
  EXPECT_GT(m.num_tets(), 10u);
  for (const glm::dvec3& p : m.points) EXPECT_LT(glm::length(p - glm::dvec3(3.75)), 1.2);
}

TEST(GenerateBounds, SizesBeyondThePointLimitAreRefusedOrStopped) {
  const std::string img = ball_image();
  // Refused before meshing, from the solid's volume.
  zs::Mesh3Criteria tiny = zs::Mesh3Criteria::from_size(0.001);
  EXPECT_NE(thrown<std::invalid_argument>([&] { zs::mesh_implicit(*zs::find_implicit("sphere"), tiny); })
                .find("cell size 0.001 needs about 2.125e+09 points for this solid (volume 4.25), over the limit of "
                      "250000"),
            std::string::npos);
  EXPECT_NE(thrown<zs::FileError>([&] { zs::mesh_gray_image(img, 2.0, false, tiny); }).find("over the limit of 250000"),
            std::string::npos);
  // A criterion the estimate does not see: refinement stops at the limit.
  zs::Mesh3Criteria fine = zs::Mesh3Criteria::from_size(0.5);
  fine.facet_distance = 1e-4;
  fine.max_points = 300;
  EXPECT_EQ(thrown<std::runtime_error>([&] { zs::mesh_implicit(*zs::find_implicit("sphere"), fine); }),
            "Mesh_3 reached the limit of 300 points (--max-points) before meeting the size criteria; use larger sizes");
}

TEST(GenerateBounds, TetgenMaxVolumeBeyondTheTetLimit) {
  zs::Plc cube = zs::box_surface(glm::dvec3(-1), glm::dvec3(1));
  // box_surface has quads: the volume check needs triangles.
  zs::Plc tri;
  tri.points = cube.points;
  for (const zs::PlcFacet& f : cube.facets) {
    const auto& q = f.polygons[0];
    tri.add_triangle(q[0], q[1], q[2]);
    tri.add_triangle(q[0], q[2], q[3]);
  }
  zs::TetgenOptions o;
  o.max_volume = 1e-12;
  EXPECT_NE(thrown<std::invalid_argument>([&] { zs::tetrahedralize(tri, o); })
                .find("max volume 1e-12 needs at least 8e+12 tets inside this surface (volume 8)"),
            std::string::npos);
  o.max_volume = 0.05;
  o.max_tets = 200;
  EXPECT_EQ(thrown<std::runtime_error>([&] { zs::tetrahedralize(tri, o); }),
            "TetGen reached the limit of 51 added points (--max-tets 200) before meeting the quality and volume bounds");
  o.max_tets = 5000;
  EXPECT_GT(zs::tetrahedralize(tri, o).num_tets(), 160u);
}

// Mesh_3 stopped sliver perturbation and exudation on a wall-clock limit,
// so runs differed (the skull image: 12195 or 12196 tets; these two: 3 and
// 4 different meshes in 3 and 4 runs before the fix).
TEST(GenerateBounds, SameInputSameMesh) {
  const std::string img = ball_image();
  const zs::Mesh3Criteria crit = zs::Mesh3Criteria::from_size(0.2);
  const zs::TetMesh a = zs::mesh_gray_image(img, 2.5, false, crit);
  for (int run = 0; run < 2; ++run) EXPECT_TRUE(same(a, zs::mesh_gray_image(img, 2.5, false, crit)));
  const zs::Mesh3Criteria c2 = zs::Mesh3Criteria::from_size(0.15);
  const zs::TetMesh b = zs::mesh_implicit(*zs::find_implicit("balls"), c2);
  for (int run = 0; run < 3; ++run) EXPECT_TRUE(same(b, zs::mesh_implicit(*zs::find_implicit("balls"), c2)));
}

// These missed the documented 10 %: post 1000 -> 1423, shell 2000 -> 2708,
// torus 1000 -> 1192.
TEST(GenerateBounds, TetsWithinTenPercentFromFifteenHundred) {
  for (const zs::ShapeInfo& s : zs::shape_catalog())
    for (size_t target : {1500u, 2000u, 3500u}) {
      SCOPED_TRACE(s.name + " " + std::to_string(target));
      zs::ShapeMeshOptions opt;
      opt.shape = s.name;
      opt.target_tets = target;
      zs::ShapeMeshReport rep;
      zs::TetMesh m = zs::mesh_shape(opt, &rep);
      EXPECT_EQ(rep.tets, m.num_tets());
      EXPECT_LE(std::abs(rep.error()), 0.1) << m.num_tets() << " tets after " << rep.runs << " runs";
      EXPECT_FALSE(rep.at_floor);
      EXPECT_LE(rep.runs, 16);
    }
  // Below what the shape meshes to: the closest, reported as such.
  zs::ShapeMeshOptions opt;
  opt.shape = "post";
  opt.target_tets = 100;
  zs::ShapeMeshReport rep;
  zs::TetMesh m = zs::mesh_shape(opt, &rep);
  EXPECT_TRUE(rep.at_floor);
  EXPECT_GT(m.num_tets(), 1000u);
  EXPECT_LT(m.num_tets(), 1400u);
}
