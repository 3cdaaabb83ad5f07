#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "geometry/tets/io/mesh_io.h"
#include "geometry/tets/io/off_io.h"
#include "base/util/file_error.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "support/test_paths.h"

namespace zs {
namespace {

TEST(OffIo, ParsesHeaderOnOneLineWithComments) {
  const TetMesh m = parse_off(
      "# a single tet\n"
      "4 1\n"
      "\n"
      "0 0 0 0.5\n1 0 0 1\n0 1 0 2\n# comment between vertices\n0 0 1 3\n"
      "0 1 2 3\n",
      "mem");
  ASSERT_EQ(m.num_points(), 4u);
  ASSERT_EQ(m.num_tets(), 1u);
  EXPECT_DOUBLE_EQ(m.scalars[0], 0.5);
  EXPECT_EQ(m.points[3].z, 1.0);
  EXPECT_EQ(m.tets[0][3], 3u);
  EXPECT_DOUBLE_EQ(signed_volume6(m, m.tets[0]), 1.0);
}

// Numbers beyond a double's range are numbers still: overflow is ±inf (the
// tet is then counted non-finite and left out), underflow is 0 or
// subnormal. from_chars alone left them at 0 (a fuzzing finding).
TEST(OffIo, OutOfRangeNumbersOverflowToInfinityAndUnderflowToZero) {
  const TetMesh m = parse_off("4 1\n0 0 0 1e999\n1 0 0 -1e999\n0 1e-400 0 2\n0 0 1 +1e400\n0 1 2 3\n", "mem");
  EXPECT_EQ(m.scalars[0], std::numeric_limits<double>::infinity());
  EXPECT_EQ(m.scalars[1], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(m.scalars[3], std::numeric_limits<double>::infinity());
  EXPECT_EQ(m.points[2].y, 0.0);
  EXPECT_EQ(count_nonfinite_tets(m), 1u);
  const TetMesh d = parse_off("4 1\n0 0 0 4.9e-324\n1 0 0 1\n0 1 0 2\n0 0 1 3\n0 1 2 3\n", "mem");
  EXPECT_GT(d.scalars[0], 0.0);  // the smallest subnormal is in range
}

TEST(OffIo, HeaderOnTwoLinesAndCrlf) {
  const TetMesh m = parse_off("4\r\n1\r\n0 0 0 0\r\n1 0 0 0\r\n0 1 0 0\r\n0 0 1 0\r\n3 2 1 0\r\n", "mem");
  EXPECT_EQ(m.num_tets(), 1u);
  EXPECT_EQ(m.tets[0][0], 3u);
}

TEST(OffIo, ErrorsNameFileAndLine) {
  try {
    parse_off("4 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 1 2 4\n", "bad.off");
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_STREQ(e.what(), "bad.off:6: vertex index 4 out of range (mesh has 4 vertices, indices are 0-based)");
  }
}

TEST(OffIo, RoundTripIsExact) {
  TetMesh m;
  m.points = {{0.1, 1e-300, -3.5e12}, {1.0 / 3.0, 2, 3}, {4, 5, 6.25}, {7, 8, 9}};
  m.scalars = {0.1, 0.2, 1.0 / 7.0, -5};
  m.tets = {{0, 1, 2, 3}, {3, 2, 1, 0}};
  const auto dir = test::scratch_dir();
  const std::string p = (dir / "rt.off").string();
  write_mesh(p, m);
  const TetMesh r = read_mesh(p);
  EXPECT_EQ(r.points, m.points);
  EXPECT_EQ(r.scalars, m.scalars);
  EXPECT_EQ(r.tets, m.tets);
  // No temporary file left beside the output.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

TEST(OffIo, FailedWriteLeavesNoFile) {
  TetMesh m;
  const std::string p = "/nonexistent-dir-zsweep/out.off";
  EXPECT_THROW(write_mesh(p, m), FileError);
  EXPECT_FALSE(std::filesystem::exists(p));
}

TEST(OffIo, SpxCountsAndOrientationSplit) {
  ZS_REQUIRE_SHARED(path, "spx.off");
  const TetMesh m = read_mesh(path);
  EXPECT_EQ(m.num_points(), 2896u);
  EXPECT_EQ(m.num_tets(), 12936u);
  const Topology t = build_topology(m);
  EXPECT_EQ(t.num_faces(), 27252u);
  EXPECT_EQ(t.num_boundary_faces, 2760u);
  const ValidationReport r = validate(m, t);
  EXPECT_EQ(r.positive_tets + r.negative_tets + r.zero_volume_tets, 12936u);
  EXPECT_EQ(r.minority_orientation(), 12u);
  EXPECT_EQ(std::max(r.positive_tets, r.negative_tets), 12924u);
  EXPECT_EQ(r.nonmanifold_faces, 0u);
  EXPECT_EQ(r.coincident_boundary_faces, 0u);
}

}  // namespace
}  // namespace zs
