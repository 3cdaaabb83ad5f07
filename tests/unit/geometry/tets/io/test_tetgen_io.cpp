// TetGen .node/.ele reading and writing through the TetGen library.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "geometry/tets/io/mesh_io.h"
#include "geometry/tets/io/tetgen_io.h"
#include "base/util/file_error.h"
#include "support/test_paths.h"

namespace fs = std::filesystem;

namespace {

zs::TetMesh two_tets() {
  zs::TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1.0 / 3.0, 1e-17, -2.5e8}};
  m.scalars = {0.1, -2.0, 3.0e-300, 4.25, 1.0 / 7.0};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  return m;
}

void write_text(const fs::path& p, const std::string& s) { std::ofstream(p) << s; }

// Runs f, expecting a FileError whose message contains `needle`, and checks
// that TetGen's own chatter did not reach stdout.
template <class F>
void expect_error(F&& f, const std::string& needle) {
  testing::internal::CaptureStdout();
  try {
    f();
    testing::internal::GetCapturedStdout();
    ADD_FAILURE() << "expected FileError containing " << needle;
  } catch (const zs::FileError& e) {
    std::string out = testing::internal::GetCapturedStdout();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    EXPECT_EQ(out, "");
  }
}

}  // namespace

TEST(TetgenIo, RoundTripPointsTetsScalars) {
  fs::path dir = zs::test::scratch_dir();
  zs::TetMesh m = two_tets();
  testing::internal::CaptureStdout();
  zs::write_tetgen((dir / "a.node").string(), m);
  zs::TetMesh r = zs::read_tetgen((dir / "a.ele").string());  // either name works
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  ASSERT_EQ(r.num_points(), m.num_points());
  ASSERT_EQ(r.num_tets(), m.num_tets());
  ASSERT_TRUE(r.has_scalars());
  for (size_t i = 0; i < m.num_points(); ++i) {
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r.points[i][k], m.points[i][k], 1e-15 * (1 + std::abs(m.points[i][k])));
    EXPECT_NEAR(r.scalars[i], m.scalars[i], 1e-15 * std::abs(m.scalars[i]));
  }
  EXPECT_EQ(r.tets, m.tets);
}

TEST(TetgenIo, NoScalarsMeansNoAttributes) {
  fs::path dir = zs::test::scratch_dir();
  zs::TetMesh m = two_tets();
  m.scalars.clear();
  zs::write_tetgen((dir / "b.node").string(), m);
  zs::TetMesh r = zs::read_tetgen((dir / "b.node").string());
  EXPECT_FALSE(r.has_scalars());
  EXPECT_EQ(r.tets, m.tets);
}

TEST(TetgenIo, WriteMeshDispatchIsAtomicAndWritesBothFiles) {
  fs::path dir = zs::test::scratch_dir();
  zs::write_mesh((dir / "c.node").string(), two_tets());
  EXPECT_TRUE(fs::exists(dir / "c.node"));
  EXPECT_TRUE(fs::exists(dir / "c.ele"));
  size_t files = 0;
  for (auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 2u) << "no temporaries left behind";
  zs::TetMesh r = zs::read_mesh((dir / "c.ele").string());
  EXPECT_EQ(r.num_tets(), 2u);
}

TEST(TetgenIo, OneBasedIndices) {
  fs::path dir = zs::test::scratch_dir();
  write_text(dir / "one.node",
             "# comment\n5 3 1 0\n1 0 0 0 10\n2 1 0 0 20\n3 0 1 0 30\n4 0 0 1 40\n5 1 1 1 50\n");
  write_text(dir / "one.ele", "2 4 0\n1 1 2 3 4\n2 2 3 4 5\n");
  zs::TetMesh r = zs::read_tetgen((dir / "one.node").string());
  ASSERT_EQ(r.num_tets(), 2u);
  EXPECT_EQ(r.tets[0], (zs::Tet{0, 1, 2, 3}));
  EXPECT_EQ(r.tets[1], (zs::Tet{1, 2, 3, 4}));
  EXPECT_DOUBLE_EQ(r.scalars[4], 50.0);
}

TEST(TetgenIo, ErrorsNameTheFileOnOneLine) {
  fs::path dir = zs::test::scratch_dir();
  const std::string good_node = "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";

  write_text(dir / "noele.node", good_node);
  expect_error([&] { zs::read_tetgen((dir / "noele.node").string()); }, "noele.ele: no such file");

  write_text(dir / "range.node", good_node);
  write_text(dir / "range.ele", "1 4 0\n0 0 1 2 9\n");
  expect_error([&] { zs::read_tetgen((dir / "range.node").string()); }, "range.ele");

  write_text(dir / "huge.node", "999999999 3 0 0\n0 0 0 0\n");
  write_text(dir / "huge.ele", "1 4 0\n0 0 1 2 3\n");
  expect_error([&] { zs::read_tetgen((dir / "huge.node").string()); }, "huge.node: header says");

  write_text(dir / "trunc.node", "6 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n5\n");
  write_text(dir / "trunc.ele", "1 4 0\n0 0 1 2 3\n");
  expect_error([&] { zs::read_tetgen((dir / "trunc.node").string()); }, "trunc.node");

  write_text(dir / "dim2.node", "3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n");
  write_text(dir / "dim2.ele", "1 4 0\n0 0 1 2 3\n");
  expect_error([&] { zs::read_tetgen((dir / "dim2.node").string()); }, "dimension is 2");

  write_text(dir / "text.node", "hello world\n");
  write_text(dir / "text.ele", "1 4 0\n0 0 1 2 3\n");
  expect_error([&] { zs::read_tetgen((dir / "text.node").string()); }, "text.node");

  expect_error([&] { zs::write_tetgen((dir / "missing-dir" / "x.node").string(), two_tets()); },
               "x.node");
}
