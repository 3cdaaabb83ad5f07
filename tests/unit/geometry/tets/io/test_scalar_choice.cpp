// Which scalar a mesh reader picks (issue 38, items 7 and 8): a name that is
// not there is an error listing what is; with no name, a constant default
// (a uniform free stream) gives way to the first array that varies.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "geometry/tets/io/mesh_io.h"
#include "support/test_paths.h"
#include "base/util/file_error.h"

namespace zs {
namespace {

namespace fs = std::filesystem;

// One tet; 'Density' (the active scalars) is constant, 'height' varies.
std::string legacy_vtk(bool density_varies) {
  return std::string(R"(# vtk DataFile Version 3.0
one tet
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 4 double
0 0 0  1 0 0  0 1 0  0 0 1
CELLS 1 5
4 0 1 2 3
CELL_TYPES 1
10
POINT_DATA 4
SCALARS Density double 1
LOOKUP_TABLE default
)") + (density_varies ? "1 2 3 4" : "1 1 1 1") + R"(
SCALARS height double 1
LOOKUP_TABLE default
0 0 0 1
)";
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = test::scratch_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

TEST(ScalarChoice, ConstantDefaultGivesWayToTheFirstArrayThatVaries) {
  const TetMesh m = read_mesh(write("c.vtk", legacy_vtk(false)).string());
  EXPECT_EQ(m.scalar_name, "height");
  EXPECT_EQ(m.scalar_choice, "'Density' is constant (1)");
  EXPECT_EQ(m.scalars[3], 1.0);
}

TEST(ScalarChoice, NamedOrVaryingDefaultIsKept) {
  const fs::path c = write("c.vtk", legacy_vtk(false));
  ReadOptions named;
  named.scalar = "Density";
  const TetMesh a = read_mesh(c.string(), named);  // asked for: kept, constant or not
  EXPECT_EQ(a.scalar_name, "Density");
  EXPECT_EQ(a.scalar_choice, "");
  const TetMesh b = read_mesh(write("v.vtk", legacy_vtk(true)).string());
  EXPECT_EQ(b.scalar_name, "Density");
  EXPECT_EQ(b.scalar_choice, "");
}

TEST(ScalarChoice, UnknownNameOnAnOffMeshListsItsScalar) {
  const fs::path off = write("t.off", "4 1\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n0 1 2 3\n");
  ReadOptions o;
  o.scalar = "nosuch";
  try {
    read_mesh(off.string(), o);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()), off.string() + ": no array named 'nosuch'; available: scalar (point)");
  }
  o.scalar = "scalar";
  EXPECT_EQ(read_mesh(off.string(), o).num_tets(), 1u);
}

TEST(ScalarChoice, SolutionFileForANonPlot3dMeshIsRefused) {
  const fs::path off = write("t.off", "4 1\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n0 1 2 3\n");
  ReadOptions o;
  o.q_path = "q.bin";
  EXPECT_THROW(read_mesh(off.string(), o), FileError);
}

// The oxygen post (shared dataset): Density is 1 everywhere.
TEST(ScalarChoice, OxygenPostPicksAVaryingFunction) {
  const std::string xyz = test::shared_dataset("postxyz.bin"), q = test::shared_dataset("postq.bin");
  if (xyz.empty() || q.empty()) GTEST_SKIP() << "postxyz.bin/postq.bin not in the shared datasets (ZSWEEP_SHARED)";
  ReadOptions o;
  o.q_path = q;
  const TetMesh m = read_mesh(xyz, o);
  EXPECT_EQ(m.scalar_name, "Pressure");
  EXPECT_EQ(m.scalar_choice, "'Density' is constant (1)");
  o.scalar = "density";
  const TetMesh d = read_mesh(xyz, o);
  EXPECT_EQ(d.scalar_name, "Density");
  EXPECT_EQ(d.scalar_choice, "");
}

}  // namespace
}  // namespace zs
