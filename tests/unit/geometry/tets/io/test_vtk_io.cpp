// VTK-backed readers/writer (src/geometry/tets/io/vtk_*.cpp, plot3d_reader.cpp):
// small synthetic files for exact behaviour, shared datasets for real counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "geometry/tets/io/vtk_io.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "base/util/file_error.h"
#include "geometry/tets/tet_mesh.h"
#include "support/test_paths.h"

namespace {

using zs::FileError;
using zs::Topology;
using zs::ValidationReport;
using zs::build_topology;
using zs::validate;
using zs::ReadOptions;
using zs::TetMesh;
namespace fs = std::filesystem;

void write_text(const fs::path& p, const std::string& s) {
  std::ofstream(p, std::ios::binary) << s;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// Expects a FileError whose message names the file; returns the message.
template <class F>
std::string expect_mesh_error(F&& f, const std::string& path) {
  try {
    f();
  } catch (const FileError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "multi-line: " << msg;
    return msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no FileError for " << path;
  return {};
}

bool has_note(const TetMesh& m, const std::string& part) {
  return std::any_of(m.notes.begin(), m.notes.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

std::string all_notes(const TetMesh& m) {
  std::string s;
  for (const auto& n : m.notes) s += n + " | ";
  return s;
}

size_t zero_volume_tets(const TetMesh& m) {
  size_t z = 0;
  for (const auto& t : m.tets) z += zs::signed_volume6(m, t) == 0.0;
  return z;
}

// Counts how many tets use each face; a conforming tet mesh has each face
// used once (boundary) or twice (interior), never more.
std::map<std::array<uint32_t, 3>, int> face_counts(const TetMesh& m) {
  std::map<std::array<uint32_t, 3>, int> faces;
  for (const auto& t : m.tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<uint32_t, 3> f;
      int n = 0;
      for (int k = 0; k < 4; ++k)
        if (k != skip) f[n++] = t[k];
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  return faces;
}

std::pair<double, double> scalar_range(const TetMesh& m) {
  auto [lo, hi] = std::minmax_element(m.scalar_values().begin(), m.scalar_values().end());
  return {*lo, *hi};
}

// Two hexes sharing a face, a tet on top, and a stray quad: exercises
// splitting, pass-through, and dropping 2-D cells.
const char* kMixedLegacy = R"(# vtk DataFile Version 3.0
mixed
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 13 double
0 0 0  1 0 0  1 1 0  0 1 0
0 0 1  1 0 1  1 1 1  0 1 1
2 0 0  2 1 0  2 0 1  2 1 1
0.5 0.5 2
CELLS 4 28
8 0 1 2 3 4 5 6 7
8 1 8 9 2 5 10 11 6
4 4 5 6 12
4 0 1 8 9
CELL_TYPES 4
12
12
10
9
POINT_DATA 13
SCALARS temp double 1
LOOKUP_TABLE default
0 1 2 3 4 5 6 7 8 9 10 11 12
SCALARS other float 1
LOOKUP_TABLE default
0 0 0 0 0 0 0 0 0 0 0 0 7
VECTORS vel double
1 0 0  0 2 0  0 0 3  0 0 0  0 0 0  0 0 0  0 0 0  0 0 0  0 0 0  0 0 0  0 0 0  0 0 0  3 4 0
)";

// ------------------------------------------------------------------ writer

TEST(VtkIo, VtuRoundTripIsExact) {
  TetMesh m;
  m.points = {{0.1, 1.0 / 3.0, -2.5e-300},
              {1.0, 0.0, 0.0},
              {0.0, 1.0, 1e300},
              {0.0, 0.0, 1.0},
              {std::nextafter(1.0, 2.0), 1.0, 1.0}};
  m.scalars = {-1.0 / 7.0, 0.0, 3.14159265358979, 1e-310, 42.0};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.scalar_name = "temperature";
  const auto path = (zs::test::scratch_dir() / "rt.vtu").string();
  zs::write_vtu(path, m);
  TetMesh r = zs::read_vtk(path, {});
  ASSERT_EQ(r.points.size(), m.points.size());
  for (size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(r.points[i].x, m.points[i].x);
    EXPECT_EQ(r.points[i].y, m.points[i].y);
    EXPECT_EQ(r.points[i].z, m.points[i].z);
  }
  EXPECT_EQ(r.tets, m.tets);
  EXPECT_EQ(r.scalars, m.scalars);
  EXPECT_EQ(r.scalar_name, "temperature");
  EXPECT_NE(read_bytes(path).find("appended"), std::string::npos);
}

TEST(VtkIo, VtuDefaultScalarNameAndNoScalar) {
  const auto dir = zs::test::scratch_dir();
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tets = {{0, 1, 2, 3}};
  m.scalars = {1, 2, 3, 4};
  zs::write_vtu((dir / "a.vtu").string(), m);
  EXPECT_EQ(zs::read_vtk((dir / "a.vtu").string(), {}).scalar_name, "scalar");
  m.scalars.clear();
  zs::write_vtu((dir / "b.vtu").string(), m);
  TetMesh r = zs::read_vtk((dir / "b.vtu").string(), {});
  EXPECT_FALSE(r.has_scalars());
  EXPECT_EQ(r.num_tets(), 1u);
}

TEST(VtkIo, VtuWriteFailureIsFileError) {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tets = {{0, 1, 2, 3}};
  const std::string bad = "/nonexistent-dir-zsweep/x.vtu";
  std::string msg = expect_mesh_error([&] { zs::write_vtu(bad, m); }, bad);
  EXPECT_NE(msg.find("cannot write"), std::string::npos) << msg;
  m.tets = {{0, 1, 2, 9}};  // out of range: refused, not written
  const auto path = (zs::test::scratch_dir() / "bad.vtu").string();
  expect_mesh_error([&] { zs::write_vtu(path, m); }, path);
}

// ------------------------------------------------------------------ reader

TEST(VtkIo, LegacyMixedCellsSplitAndDropped) {
  const auto path = (zs::test::scratch_dir() / "mixed.vtk").string();
  write_text(path, kMixedLegacy);
  TetMesh m = zs::read_vtk(path, {});
  EXPECT_EQ(m.scalar_name, "temp");
  EXPECT_EQ(m.num_points(), 13u);
  // The tet passes through; each hex becomes 5 or 6 tets.
  EXPECT_GE(m.num_tets(), 11u);
  EXPECT_LE(m.num_tets(), 13u);
  EXPECT_EQ(zero_volume_tets(m), 0u);
  double vol6 = 0;
  for (const auto& t : m.tets) vol6 += std::abs(zs::signed_volume6(m, t));
  EXPECT_NEAR(vol6 / 6.0, 2.0 + 1.0 / 6.0, 1e-12);
  for (auto [f, n] : face_counts(m)) EXPECT_LE(n, 2);
  EXPECT_TRUE(has_note(m, "dropped 1 vtkQuad")) << all_notes(m);
  EXPECT_TRUE(has_note(m, "split 2 non-tet")) << all_notes(m);
  // Scalars follow their points.
  for (size_t i = 0; i < m.num_points(); ++i) EXPECT_EQ(m.scalars[i], static_cast<double>(i));
}

TEST(VtkIo, ScalarByNameVectorMagnitudeAndUnknownName) {
  const auto path = (zs::test::scratch_dir() / "mixed.vtk").string();
  write_text(path, kMixedLegacy);
  ReadOptions o;
  o.scalar = "other";
  TetMesh m = zs::read_vtk(path, o);
  EXPECT_EQ(m.scalar_name, "other");
  EXPECT_EQ(m.scalars[12], 7.0);
  o.scalar = "vel";
  m = zs::read_vtk(path, o);
  EXPECT_EQ(m.scalars[0], 1.0);
  EXPECT_EQ(m.scalars[12], 5.0);
  EXPECT_TRUE(has_note(m, "magnitude")) << all_notes(m);
  o.scalar = "nope";
  std::string msg = expect_mesh_error([&] { zs::read_vtk(path, o); }, path);
  EXPECT_NE(msg.find("nope"), std::string::npos) << msg;
  EXPECT_NE(msg.find("temp (point)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("vel (point)"), std::string::npos) << msg;
}

// Two tets with cell data (stress 2 and 4) and a point array beside them,
// then a hexahedron (one cell, value 9) that the reader splits into tets.
constexpr const char* kCellsVtk = R"(# vtk DataFile Version 3.0
cells
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 13 float
0 0 0  1 0 0  0 1 0  0 0 1  1 1 1
3 0 0  4 0 0  4 1 0  3 1 0  3 0 1  4 0 1  4 1 1  3 1 1
CELLS 3 19
4 0 1 2 3
4 1 2 3 4
8 5 6 7 8 9 10 11 12
CELL_TYPES 3
10
10
12
CELL_DATA 3
SCALARS stress float 1
LOOKUP_TABLE default
2 4 9
POINT_DATA 13
SCALARS temp float 1
LOOKUP_TABLE default
0 1 2 3 4 5 6 7 8 9 10 11 12
)";

TEST(VtkIo, CellDataStayPerTetAndSplitCellsKeepTheirValue) {
  const auto path = (zs::test::scratch_dir() / "cells.vtk").string();
  write_text(path, kCellsVtk);
  ReadOptions opt;
  opt.scalar = "stress";
  TetMesh m = zs::read_vtk(path, opt);
  EXPECT_EQ(m.scalar_name, "stress");
  EXPECT_TRUE(has_note(m, "one value per tet")) << all_notes(m);
  EXPECT_TRUE(m.scalars.empty());
  ASSERT_EQ(m.cell_scalars.size(), m.num_tets());
  ASSERT_GE(m.num_tets(), 7u);  // 2 tets + a hex in 5 or 6
  EXPECT_EQ(m.cell_scalars[0], 2.0);
  EXPECT_EQ(m.cell_scalars[1], 4.0);
  for (size_t t = 2; t < m.num_tets(); ++t) {
    EXPECT_EQ(m.cell_scalars[t], 9.0) << t;
    for (uint32_t v : m.tets[t]) EXPECT_GE(m.points[v].x, 3.0) << "tet " << t << " is the hex's";
  }
  // The default array is the point one; the cell one by association.
  EXPECT_EQ(zs::read_vtk(path, {}).scalar_name, "temp");
  ReadOptions cell;
  cell.association = zs::ScalarAssociation::Cell;
  const TetMesh c = zs::read_vtk(path, cell);
  EXPECT_EQ(c.scalar_name, "stress");
  EXPECT_EQ(c.cell_scalars, m.cell_scalars);
}

TEST(VtkIo, CellDataAveragedOntoPointsOnRequest) {
  const auto path = (zs::test::scratch_dir() / "cells.vtk").string();
  write_text(path, kCellsVtk);
  ReadOptions opt;
  opt.scalar = "stress";
  opt.association = zs::ScalarAssociation::CellToPoint;
  TetMesh m = zs::read_vtk(path, opt);
  EXPECT_EQ(m.scalar_name, "stress");
  EXPECT_TRUE(has_note(m, "averaged onto points")) << all_notes(m);
  EXPECT_TRUE(m.cell_scalars.empty());
  ASSERT_EQ(m.scalars.size(), m.num_points());
  EXPECT_EQ(m.scalars[0], 2.0);
  EXPECT_EQ(m.scalars[1], 3.0);  // shared by both tets: mean
  EXPECT_EQ(m.scalars[4], 4.0);
  EXPECT_EQ(m.scalars[5], 9.0);
}

TEST(VtkIo, AssociationThatTheArrayDoesNotHaveIsAnError) {
  const auto path = (zs::test::scratch_dir() / "cells.vtk").string();
  write_text(path, kCellsVtk);
  ReadOptions opt;
  opt.scalar = "stress";
  opt.association = zs::ScalarAssociation::Point;
  EXPECT_NE(expect_mesh_error([&] { zs::read_vtk(path, opt); }, path).find("'stress' is cell data"), std::string::npos);
  opt.scalar = "temp";
  opt.association = zs::ScalarAssociation::Cell;
  EXPECT_NE(expect_mesh_error([&] { zs::read_vtk(path, opt); }, path).find("'temp' is point data"), std::string::npos);
  zs::ScalarAssociation a;
  EXPECT_TRUE(zs::parse_association("cell_to_point", &a));
  EXPECT_EQ(a, zs::ScalarAssociation::CellToPoint);
  EXPECT_FALSE(zs::parse_association("cells", &a));
}

TEST(VtkIo, VtuRoundTripKeepsCellData) {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.cell_scalars = {-1.0 / 7.0, 1e-310};
  m.scalar_name = "pressure";
  const auto path = (zs::test::scratch_dir() / "rt-cells.vtu").string();
  zs::write_vtu(path, m);
  const TetMesh r = zs::read_vtk(path, {});
  EXPECT_EQ(r.cell_scalars, m.cell_scalars);
  EXPECT_TRUE(r.scalars.empty());
  EXPECT_EQ(r.scalar_name, "pressure");
}

TEST(VtkIo, QuadraticTetUsesCornersOnly) {
  const auto path = (zs::test::scratch_dir() / "quad.vtk").string();
  write_text(path, R"(# vtk DataFile Version 3.0
quadratic tet
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 10 double
0 0 0  2 0 0  0 2 0  0 0 2
1 0 0  1 1 0  0 1 0  0 0 1  1 0 1  0 1 1
CELLS 1 11
10 0 1 2 3 4 5 6 7 8 9
CELL_TYPES 1
24
POINT_DATA 10
SCALARS s double 1
LOOKUP_TABLE default
0 1 2 3 4 5 6 7 8 9
)");
  TetMesh m = zs::read_vtk(path, {});
  ASSERT_EQ(m.num_tets(), 1u);
  EXPECT_EQ(m.num_points(), 4u);  // mid-edge nodes dropped
  EXPECT_EQ(m.scalars, (std::vector<double>{0, 1, 2, 3}));
  EXPECT_NE(zs::signed_volume6(m, m.tets[0]), 0.0);
  EXPECT_TRUE(has_note(m, "corner nodes")) << all_notes(m);
}

TEST(VtkIo, GarbageAndTruncatedFilesThrow) {
  const auto dir = zs::test::scratch_dir();
  std::mt19937 rng(7);
  std::string junk(4096, '\0');
  for (auto& c : junk) c = static_cast<char>(rng());
  const auto gvtu = (dir / "garbage.vtu").string();
  const auto gvtk = (dir / "garbage.vtk").string();
  write_text(gvtu, junk);
  write_text(gvtk, junk);
  expect_mesh_error([&] { zs::read_vtk(gvtu, {}); }, gvtu);
  expect_mesh_error([&] { zs::read_vtk(gvtk, {}); }, gvtk);

  // Truncated legacy file: header and part of the points only.
  const auto tvtk = (dir / "trunc.vtk").string();
  std::string legacy = kMixedLegacy;
  write_text(tvtk, legacy.substr(0, legacy.find("CELLS") - 20));
  expect_mesh_error([&] { zs::read_vtk(tvtk, {}); }, tvtk);

  // Truncated XML file: a real .vtu cut in half.
  TetMesh m;
  for (int i = 0; i < 200; ++i) m.points.push_back({i * 1.0, i * i * 1.0, 1.0 / (i + 1)});
  for (uint32_t i = 0; i + 3 < 200; ++i) m.tets.push_back({i, i + 1, i + 2, i + 3});
  m.scalars.assign(200, 1.5);
  const auto full = (dir / "full.vtu").string();
  zs::write_vtu(full, m);
  const std::string bytes = read_bytes(full);
  const auto tvtu = (dir / "trunc.vtu").string();
  write_text(tvtu, bytes.substr(0, bytes.size() / 2));
  expect_mesh_error([&] { zs::read_vtk(tvtu, {}); }, tvtu);

  const auto empty = (dir / "empty.vtu").string();
  write_text(empty, "");
  expect_mesh_error([&] { zs::read_vtk(empty, {}); }, empty);
  const auto missing = (dir / "missing.vtk").string();
  std::string msg = expect_mesh_error([&] { zs::read_vtk(missing, {}); }, missing);
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(VtkIo, TruncatedBinaryLegacyThrows) {
  ZS_REQUIRE_SHARED(iron, "ironProt.vtk");
  // The legacy reader only warns on short binary data and returns what it
  // got; that must still be an error.
  const std::string bytes = read_bytes(iron);
  const auto path = (zs::test::scratch_dir() / "iron-cut.vtk").string();
  write_text(path, bytes.substr(0, bytes.size() / 3));
  std::string msg = expect_mesh_error([&] { zs::read_vtk(path, {}); }, path);
  EXPECT_EQ(msg.find("Generic Warning"), std::string::npos) << msg;
}

TEST(VtkIo, NoThreeDCellsThrows) {
  const auto path = (zs::test::scratch_dir() / "tri.vtk").string();
  write_text(path, R"(# vtk DataFile Version 3.0
triangle
ASCII
DATASET POLYDATA
POINTS 3 float
0 0 0  1 0 0  0 1 0
POLYGONS 1 4
3 0 1 2
)");
  expect_mesh_error([&] { zs::read_vtk(path, {}); }, path);
}

TEST(VtkIo, KieferQuadraticTets) {
  ZS_REQUIRE_SHARED(path, "kiefer.vtu");
  TetMesh m = zs::read_vtk(path, {});
  EXPECT_EQ(m.num_tets(), 56786u);
  EXPECT_TRUE(has_note(m, "cell data")) << all_notes(m);
  EXPECT_TRUE(has_note(m, "corner nodes")) << all_notes(m);
  EXPECT_LT(m.num_points(), 102578u);  // mid-edge nodes gone
  EXPECT_EQ(m.cell_scalars.size(), m.num_tets());  // cell data, one value per tet
  EXPECT_EQ(zero_volume_tets(m), 0u);
  for (const auto& t : m.tets)
    for (uint32_t v : t) ASSERT_LT(v, m.num_points());
  auto [lo, hi] = scalar_range(m);
  EXPECT_LT(lo, hi);
  std::cout << "kiefer: " << m.num_points() << " points, " << m.num_tets() << " tets, '"
            << m.scalar_name << "' [" << lo << ", " << hi << "]; " << all_notes(m) << "\n";
}

TEST(VtkIo, IronProtStructuredPoints) {
  ZS_REQUIRE_SHARED(path, "ironProt.vtk");
  TetMesh m = zs::read_vtk(path, {});
  // vtkDataSetTriangleFilter splits each voxel of the 68^3 image into 5 tets.
  EXPECT_EQ(m.num_tets(), 5u * 67 * 67 * 67);
  EXPECT_EQ(m.num_points(), 68u * 68 * 68);
  EXPECT_EQ(zero_volume_tets(m), 0u);
  for (auto [f, n] : face_counts(m)) ASSERT_LE(n, 2);
  EXPECT_TRUE(has_note(m, "split into")) << all_notes(m);
  auto [lo, hi] = scalar_range(m);
  std::cout << "ironProt: " << m.num_points() << " points, " << m.num_tets() << " tets, '"
            << m.scalar_name << "' [" << lo << ", " << hi << "]\n";
}

// ------------------------------------------------------------------ PLOT3D

void put_be32(std::string& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xff));
}
void put_be_float(std::string& out, float f) {
  uint32_t v;
  std::memcpy(&v, &f, 4);
  put_be32(out, v);
}

// Writes a single-block big-endian PLOT3D grid (slightly sheared so no two
// points coincide) and a solution with density = 1 + x.
void write_plot3d(const fs::path& xyz, const fs::path& q, int ni, int nj, int nk,
                  const std::vector<int>* iblank = nullptr) {
  std::string g, s;
  for (int d : {ni, nj, nk}) put_be32(g, static_cast<uint32_t>(d));
  const int n = ni * nj * nk;
  std::vector<float> x(n), y(n), z(n);
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const int p = i + ni * (j + nj * k);
        x[p] = static_cast<float>(i) + 0.25f * static_cast<float>(j);
        y[p] = static_cast<float>(j);
        z[p] = static_cast<float>(k) + 0.125f * static_cast<float>(i);
      }
  for (const auto* a : {&x, &y, &z})
    for (float v : *a) put_be_float(g, v);
  if (iblank)
    for (int v : *iblank) put_be32(g, static_cast<uint32_t>(v));
  for (int d : {ni, nj, nk}) put_be32(s, static_cast<uint32_t>(d));
  for (float v : {0.5f, 0.0f, 1000.0f, 0.0f}) put_be_float(s, v);
  for (int v = 0; v < 5; ++v)
    for (int p = 0; p < n; ++p) put_be_float(s, v == 0 ? 1.0f + x[p] : v == 4 ? 2.5f : 0.1f);
  write_text(xyz, g);
  write_text(q, s);
}

TEST(Plot3d, FiveTetSplitConformsOnSyntheticGrid) {
  const auto dir = zs::test::scratch_dir();
  const int ni = 4, nj = 3, nk = 3;  // 3x2x2 hexes: both parities in each direction
  write_plot3d(dir / "g.xyz", dir / "g.q", ni, nj, nk);
  ReadOptions o;
  o.q_path = (dir / "g.q").string();
  TetMesh m = zs::read_plot3d((dir / "g.xyz").string(), o);
  const size_t hexes = (ni - 1) * (nj - 1) * (nk - 1);
  ASSERT_EQ(m.num_tets(), 5 * hexes);
  EXPECT_EQ(m.num_points(), static_cast<size_t>(ni * nj * nk));
  EXPECT_EQ(m.scalar_name, "Density");
  double vol6 = 0;
  for (const auto& t : m.tets) {
    const double v = zs::signed_volume6(m, t);
    EXPECT_GT(v, 0.0);  // non-degenerate and consistently oriented
    vol6 += v;
  }
  EXPECT_NEAR(vol6 / 6.0, (ni - 1) * (nj - 1) * (nk - 1), 1e-9);  // shear keeps volume
  // Boundary quads: 2 triangles each, used once; all other faces twice.
  const size_t boundary_quads =
      2 * ((ni - 1) * (nj - 1) + (nj - 1) * (nk - 1) + (ni - 1) * (nk - 1));
  size_t once = 0, twice = 0, other = 0;
  for (auto [f, n] : face_counts(m)) (n == 1 ? once : n == 2 ? twice : other)++;
  EXPECT_EQ(other, 0u);
  EXPECT_EQ(once, 2 * boundary_quads);
  EXPECT_EQ(4 * m.num_tets(), once + 2 * twice);
  for (size_t i = 0; i < m.num_points(); ++i)
    EXPECT_FLOAT_EQ(static_cast<float>(m.scalars[i]), 1.0f + static_cast<float>(m.points[i].x));
  EXPECT_TRUE(has_note(m, "hexes")) << all_notes(m);
}

TEST(Plot3d, IblankSkipsHexesAndUnknownFunctionThrows) {
  const auto dir = zs::test::scratch_dir();
  const int ni = 4, nj = 3, nk = 3;
  std::vector<int> ib(ni * nj * nk, 1);
  ib[0] = 0;   // corner point: only hex (0,0,0) touches it
  ib[1] = -1;  // fringe point: kept
  write_plot3d(dir / "b.xyz", dir / "b.q", ni, nj, nk, &ib);
  ReadOptions o;
  o.q_path = (dir / "b.q").string();
  TetMesh m = zs::read_plot3d((dir / "b.xyz").string(), o);
  EXPECT_EQ(m.num_tets(), 5u * (3 * 2 * 2 - 1));
  EXPECT_TRUE(has_note(m, "IBLANK skipped 1 hexes")) << all_notes(m);

  o.scalar = "bogus";
  const auto xyz = (dir / "b.xyz").string();
  std::string msg = expect_mesh_error([&] { zs::read_plot3d(xyz, o); }, xyz);
  EXPECT_NE(msg.find("velocity-magnitude"), std::string::npos) << msg;
  o.scalar = "internal-energy";  // computed here, not by VTK
  m = zs::read_plot3d(xyz, o);
  // E/rho - |m|^2/(2 rho^2) with rho = 1 + x, m = (0.1, 0.1, 0.1), E = 2.5.
  const double rho = 1.0 + m.points[5].x;
  EXPECT_NEAR(m.scalars[5], 2.5 / rho - 0.5 * 0.03 / (rho * rho), 1e-5);
}

TEST(Plot3d, BadInputsThrow) {
  const auto dir = zs::test::scratch_dir();
  write_plot3d(dir / "g.xyz", dir / "g.q", 3, 3, 3);
  const auto xyz = (dir / "g.xyz").string();
  ReadOptions o;
  expect_mesh_error([&] { zs::read_plot3d(xyz, o); }, xyz);  // no q file given
  o.q_path = (dir / "missing.q").string();
  expect_mesh_error([&] { zs::read_plot3d(xyz, o); }, o.q_path);
  std::mt19937 rng(3);
  std::string junk(5000, '\0');
  for (auto& c : junk) c = static_cast<char>(rng());
  write_text(dir / "junk.xyz", junk);
  o.q_path = (dir / "g.q").string();
  const auto jx = (dir / "junk.xyz").string();
  expect_mesh_error([&] { zs::read_plot3d(jx, o); }, jx);
  // VTK's auto-detection alone let about a third of random files through to
  // a crash; the size gate must reject them all.
  for (int trial = 0; trial < 30; ++trial) {
    junk.resize(16 + rng() % 20000);
    for (auto& c : junk) c = static_cast<char>(rng());
    write_text(jx, junk);
    expect_mesh_error([&] { zs::read_plot3d(jx, o); }, jx);
  }
  // A grid cut short, and a solution file that does not belong to the grid.
  const std::string grid = read_bytes(dir / "g.xyz");
  write_text(jx, grid.substr(0, grid.size() - 8));
  expect_mesh_error([&] { zs::read_plot3d(jx, o); }, jx);
  write_plot3d(dir / "h.xyz", dir / "h.q", 4, 3, 3);
  o.q_path = (dir / "h.q").string();
  expect_mesh_error([&] { zs::read_plot3d(xyz, o); }, xyz);
}

TEST(Plot3d, MultiBlockConcatenatedAndMerged) {
  // Two 3x3x3 blocks; the second starts where the first ends in x, so they
  // share one 3x3 face of points that the merge must fuse.
  const auto dir = zs::test::scratch_dir();
  std::string g, q;
  put_be32(g, 2);
  put_be32(q, 2);
  for (int b = 0; b < 2; ++b)
    for (int d = 0; d < 3; ++d) {
      put_be32(g, 3);
      put_be32(q, 3);
    }
  for (int b = 0; b < 2; ++b) {
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i)
            put_be_float(g, static_cast<float>(c == 0 ? i + 2 * b : c == 1 ? j : k));
    for (float v : {0.5f, 0.0f, 1000.0f, 0.0f}) put_be_float(q, v);
    for (int v = 0; v < 5; ++v)
      for (int p = 0; p < 27; ++p) put_be_float(q, v == 0 ? static_cast<float>(b + 1) : 1.0f);
  }
  write_text(dir / "m.xyz", g);
  write_text(dir / "m.q", q);
  ReadOptions o;
  o.q_path = (dir / "m.q").string();
  TetMesh m = zs::read_plot3d((dir / "m.xyz").string(), o);
  EXPECT_EQ(m.num_tets(), 2u * 5 * 8);
  EXPECT_EQ(m.num_points(), 2u * 27 - 9);
  EXPECT_TRUE(has_note(m, "2 blocks")) << all_notes(m);
  EXPECT_TRUE(has_note(m, "merged 9 duplicate points")) << all_notes(m);
  // Shared points keep the first block's scalar.
  for (size_t i = 0; i < m.num_points(); ++i)
    EXPECT_EQ(m.scalars[i], m.points[i].x <= 2.0 ? 1.0 : 2.0) << i;
  // Parity is per block; (2 + j + k) has the parity of (0 + j + k), so the
  // seam conforms: no face is used more than twice, and only boundary faces once.
  size_t once = 0;
  for (auto [f, n] : face_counts(m)) {
    EXPECT_LE(n, 2);
    once += n == 1;
  }
  EXPECT_EQ(once, 2u * 2 * (4 * 2 + 2 * 2 + 4 * 2));
}

TetMesh read_shared_plot3d(const std::string& xyz, const std::string& q, const std::string& fn) {
  ReadOptions o;
  o.q_path = q;
  o.scalar = fn;
  return zs::read_plot3d(xyz, o);
}

TEST(Plot3d, BluntFin) {
  ZS_REQUIRE_SHARED(xyz, "bluntfinxyz.bin");
  ZS_REQUIRE_SHARED(q, "bluntfinq.bin");
  TetMesh m = read_shared_plot3d(xyz, q, "");
  EXPECT_EQ(m.num_tets(), 187395u);   // 5 x 39x31x31
  EXPECT_EQ(m.num_points(), 40921u);  // 40,960 before merging
  EXPECT_EQ(m.scalar_name, "Density");
  EXPECT_TRUE(has_note(m, "merged 39 duplicate points")) << all_notes(m);
  // The collapsed grid cells become 77 zero-volume tets, counted not dropped.
  const Topology topo = build_topology(m);
  const ValidationReport r = validate(m, topo);
  EXPECT_EQ(r.zero_volume_tets, 77u);
  EXPECT_EQ(r.negative_tets, 0u);
  EXPECT_EQ(r.coincident_boundary_faces, 0u);
  auto [lo, hi] = scalar_range(m);
  std::cout << "bluntfin: zero-volume tets " << zero_volume_tets(m) << ", density [" << lo << ", "
            << hi << "]; " << all_notes(m) << "\n";
}

TEST(Plot3d, PostWithIblank) {
  ZS_REQUIRE_SHARED(xyz, "postxyz.bin");
  ZS_REQUIRE_SHARED(q, "postq.bin");
  TetMesh m = read_shared_plot3d(xyz, q, "velocity-magnitude");
  EXPECT_EQ(m.num_tets(), 513375u);
  EXPECT_EQ(m.num_points(), 108300u);  // 109,744 before merging
  EXPECT_EQ(m.scalar_name, "VelocityMagnitude");
  EXPECT_TRUE(has_note(m, "IBLANK skipped")) << all_notes(m);
  // Face count as in the seed's Table 4.1; the O-grid seam is stitched by the
  // point merge but its two sides split their quads along different
  // diagonals: 37 x 37 quads, 2 triangles a side, boundary on both sides.
  const Topology topo = build_topology(m);
  EXPECT_EQ(topo.num_faces(), 1040588u);
  const ValidationReport r = validate(m, topo);
  EXPECT_EQ(r.coincident_boundary_faces, 37u * 37u * 4u);
  EXPECT_EQ(r.zero_volume_tets, 0u);
  auto [lo, hi] = scalar_range(m);
  EXPECT_LT(lo, hi);
  std::cout << "post: zero-volume tets " << zero_volume_tets(m) << ", |v| [" << lo << ", " << hi
            << "]; " << all_notes(m) << "\n";
}

TEST(Plot3d, Combustor) {
  ZS_REQUIRE_SHARED(xyz, "combxyz.bin");
  ZS_REQUIRE_SHARED(q, "combq.bin");
  TetMesh m = read_shared_plot3d(xyz, q, "density");
  EXPECT_EQ(m.num_tets(), 215040u);  // 5 x 56x32x24
  auto [lo, hi] = scalar_range(m);
  std::cout << "comb: " << m.num_points() << " points, zero-volume tets " << zero_volume_tets(m)
            << ", density [" << lo << ", " << hi << "]; " << all_notes(m) << "\n";
}

}  // namespace
