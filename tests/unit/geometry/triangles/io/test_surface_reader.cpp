// The triangle surface readers (src/geometry/triangles/io/surface_reader.h):
// OFF, OBJ, STL and PLY split into triangles with their counts, and
// malformed files refused with one line naming the file.
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/util/file_error.h"
#include "geometry/triangles/io/surface_reader.h"
#include "support/test_paths.h"
#include "support/test_surface_meshes.h"

namespace zs {
namespace {

using test::kCubeQuads;
using test::write_text;

TEST(Surfaces, ReadersSplitPolygonsAndCount) {
  const auto dir = test::scratch_dir();
  write_text(dir / "cube.off", kCubeQuads);
  SurfaceReadCounts c;
  const TriangleMesh m = read_surface((dir / "cube.off").string(), &c);
  EXPECT_EQ(m.num_points(), 8u);
  EXPECT_EQ(m.num_tris(), 12u);
  EXPECT_EQ(c.polygons, 6u);
  EXPECT_EQ(c.split, 6u);
  EXPECT_EQ(count_degenerate_tris(m), 0u);
  // Outward winding kept: every face normal points away from the centre.
  for (size_t t = 0; t < m.num_tris(); ++t) {
    const glm::dvec3 a = m.points[m.tris[t][0]];
    EXPECT_GT(glm::dot(face_normal(m, t), a - glm::dvec3(0.5)), 0) << t;
  }
  // The same square (a concave pentagon plus a triangle) as OBJ, ASCII STL and PLY.
  write_text(dir / "s.obj", "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 1 0\nv 0 2 0\nf 1 2 3 4 5\nl 1 3\n");
  const TriangleMesh o = read_surface((dir / "s.obj").string(), &c);
  EXPECT_EQ(o.num_tris(), 3u);  // the concave pentagon, ear-cut
  EXPECT_EQ(c.split, 1u);
  EXPECT_EQ(c.dropped, 1u);  // the line
  double area = 0;
  for (size_t t = 0; t < o.num_tris(); ++t) area += 0.5 * glm::length(face_normal(o, t));
  EXPECT_NEAR(area, 3.0, 1e-12);  // 2×2 square minus the notch of area 1
  write_text(dir / "s.stl",
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
        "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
  EXPECT_EQ(read_surface((dir / "s.stl").string()).num_tris(), 2u);
  write_text(dir / "s.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(read_surface((dir / "s.ply").string()).num_tris(), 2u);
  EXPECT_TRUE(is_surface_file((dir / "cube.off").string()));
  write_text(dir / "tets.off", "4 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 1 2 3\n");
  EXPECT_FALSE(is_surface_file((dir / "tets.off").string()));
}

TEST(Surfaces, MalformedFilesGiveOneLineErrorsNamingTheFile) {
  const auto dir = test::scratch_dir();
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"},
      {"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"},
      {"empty.obj", ""},
      {"noface.obj", "v 0 0 0\nv 1 0 0\n"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
      {"junk.ply", "ply\nthis is not a ply header\n"},
      {"junk.stl", "solid x\nfacet nonsense\n"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"},
  };
  for (const auto& [name, text] : bad) {
    write_text(dir / name, text);
    const std::string path = (dir / name).string();
    try {
      read_surface(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const FileError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
  EXPECT_THROW(read_surface((dir / "missing.obj").string()), FileError);
}

}  // namespace
}  // namespace zs
