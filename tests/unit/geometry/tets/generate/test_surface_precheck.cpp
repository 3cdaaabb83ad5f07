// The checks before CGAL 5.5's surface readers (surface_precheck.h): counts
// the file cannot hold, face sizes that do not match their lines, PLY headers
// whose types CGAL's reader would dereference as null. Each is one FileError
// naming the file and, for text, the line; valid files still read.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "geometry/tets/generate/surface_io.h"
#include "geometry/tets/generate/surface_precheck.h"
#include "base/util/file_error.h"
#include "support/test_paths.h"

namespace zs {
namespace {

const char* const kTetOff = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
const char* const kPlyBody = "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

// The FileError of read_surface on a file with these bytes, without the
// scratch directory ("" when it reads).
std::string surface_error(const std::string& name, const std::string& bytes) {
  const auto p = test::scratch_dir() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  try {
    read_surface(p.string());
  } catch (const FileError& e) {
    std::string w = e.what();
    return w.substr(w.find(name));
  }
  return "";
}

std::string ply(const std::string& vertex_props, const std::string& face_list) {
  return "ply\nformat ascii 1.0\nelement vertex 4\n" + vertex_props + "element face 4\nproperty list " + face_list +
         " vertex_indices\n" + kPlyBody;
}

TEST(SurfacePrecheck, ValidFilesStillRead) {
  EXPECT_EQ(surface_error("t.off", kTetOff), "");
  EXPECT_EQ(surface_error("t.off", std::string("# c\nOFF 4 4 0\n") + (std::strchr(kTetOff, '\n') + 7)), "");
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  EXPECT_EQ(surface_error("t.ply", ply(xyz, "uchar int")), "");
  EXPECT_EQ(surface_error("t.ply", ply("property double x\nproperty double y\nproperty double z\n", "ushort uint")), "");
}

TEST(SurfacePrecheck, OffCountsAgainstFileSize) {
  EXPECT_EQ(surface_error("a.off", "OFF\n2000000000 4 6\n0 0 0\n"),
            "a.off:2: OFF header declares 2000000000 vertices and 4 faces, more than the remaining 7 bytes can hold");
  EXPECT_EQ(surface_error("e.off", "OFF 4 4 2000000000\n0 0 0\n"),
            "e.off:1: OFF header: edge count 2000000000 is too large");
  EXPECT_EQ(surface_error("b.off", "OFF BINARY\n"), "b.off:1: binary OFF is not supported");
  EXPECT_EQ(surface_error("n.off", "nOFF 3 4 4 6\n"), "n.off:1: OFF variant 'nOFF' is not supported (expected OFF or 4OFF)");
  EXPECT_EQ(surface_error("t.off", "\n# c\nSTOFF\n4 4 0\n"), "t.off:3: OFF variant 'STOFF' is not supported (expected OFF or 4OFF)");
  EXPECT_EQ(surface_error("s.off", "SKEL 4 0\n"), "s.off: not an OFF surface (no OFF header)");
}

// CGAL sizes each face by its first number before reading the indices: a
// huge count allocated gigabytes, a negative one was a cast of a negative
// double to size_t (finding 5).
TEST(SurfacePrecheck, OffFaceCountMatchesItsLine) {
  EXPECT_EQ(surface_error("f.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n# face\n1e9 0 1 2\n"),
            "f.off:8: OFF face 0: corner count '1e9' does not match the 3 numbers after it");
  EXPECT_EQ(surface_error("g.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-3 0 1 2\n"),
            "g.off:7: OFF face 0: corner count '-3' does not match the 3 numbers after it");
  // istream >> double read "4888bsp" as 4888 (a fuzzing finding with 55 digits).
  EXPECT_EQ(surface_error("p.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n4888bsp 0 1 2\n"),
            "p.off:7: OFF face 0: '4888bsp' is not a number");
  EXPECT_EQ(surface_error("h.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 -1 2\n"),
            "h.off:7: OFF face 0: vertex index -1 out of range (4 vertices, 0-based)");
}

TEST(SurfacePrecheck, BinaryStlSizeMatchesTriangleCount) {
  std::string stl(84, ' ');
  const uint32_t n = 100000000;
  std::memcpy(&stl[80], &n, 4);
  EXPECT_EQ(surface_error("b.stl", stl), "b.stl: binary STL: 100000000 triangles need 5000000084 bytes, the file has 84");
  EXPECT_EQ(surface_error("c.stl", "xyz"), "c.stl: binary STL shorter than its 84-byte header");
}

TEST(SurfacePrecheck, PlyHeaderTypesAndCounts) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  EXPECT_EQ(surface_error("i.ply", ply("property float x\nproperty int y\nproperty float z\n", "uchar int")),
            "i.ply:5: PLY header: vertex coordinate 'y' must be float or double");
  EXPECT_EQ(surface_error("x.ply", ply("property list uchar float x\nproperty float y\nproperty float z\n", "uchar int")),
            "x.ply:4: PLY header: vertex coordinate 'x' must be float or double");
  EXPECT_EQ(surface_error("l.ply", ply(xyz, "int int")),
            "l.ply:8: PLY header: list count type 'int' (at most 16 bits: uchar or ushort)");
  EXPECT_EQ(surface_error("c.ply", "ply\nformat ascii 1.0\nelement vertex 99999999\n" + xyz + kPlyBody),
            "c.ply:3: PLY header: element counts exceed the file's 163 bytes");
  EXPECT_EQ(surface_error("m.ply", "ply\nformat binary_little_endian 1.0\nelement thing -1\nend_header\n"),
            "m.ply:3: PLY header: element count '-1' is not a number of items");
  EXPECT_EQ(surface_error("e.ply", "ply\nend_header ascii 1.0\nproperty float x\nend_header\n"),
            "e.ply:3: PLY header: property before any element");
  EXPECT_EQ(surface_error("r.ply", ply(xyz + "property uchar red\nproperty float green\nproperty uchar g\n", "uchar int")),
            "r.ply:8: PLY header: vertex colour 'green' must be uchar");
  EXPECT_EQ(surface_error("h.ply", "ply\nformat ascii 1.0\nelement halfedge 1\nproperty int source\nend_header\n1\n"),
            "h.ply:4: PLY header: halfedge 'source' must be uint");
}

}  // namespace
}  // namespace zs
