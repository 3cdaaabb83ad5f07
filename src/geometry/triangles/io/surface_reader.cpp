#include "geometry/triangles/io/surface_reader.h"
#include "geometry/triangles/io/polydata_triangles.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>

#include <CGAL/IO/OFF.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "geometry/tets/io/vtk_capture.h"
#include "geometry/triangles/surface_file.h"
#include "base/util/file_error.h"

namespace zs {

namespace fs = std::filesystem;

// Splits every polygon of `pd` with vtkTriangleFilter and copies the triangles.
TriangleMesh triangles_of_polydata(vtkPolyData* pd, const std::string& path, SurfaceReadCounts* counts) {
  SurfaceReadCounts c;
  if (vtkCellArray* polys = pd->GetPolys()) {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      ++c.polygons;
      c.split += n > 3;
      c.dropped += n < 3;
    }
  }
  c.dropped += size_t(pd->GetNumberOfLines() + pd->GetNumberOfVerts());
  auto tf = vtkSmartPointer<vtkTriangleFilter>::New();
  tf->SetInputData(pd);
  tf->PassLinesOff();
  tf->PassVertsOff();
  tf->Update();
  vtkPolyData* out = tf->GetOutput();
  TriangleMesh m;
  vtkPoints* pts = out->GetPoints();
  const vtkIdType np = pts ? pts->GetNumberOfPoints() : 0;
  m.points.resize(size_t(np));
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3];
    pts->GetPoint(i, p);
    m.points[size_t(i)] = {p[0], p[1], p[2]};
  }
  vtkCellArray* polys = out->GetPolys();
  if (polys) {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      if (n != 3) continue;
      m.tris.push_back({uint32_t(ids[0]), uint32_t(ids[1]), uint32_t(ids[2])});
    }
  }
  m.surface.assign(m.tris.size(), 0);
  for (const glm::dvec3& p : m.points)
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
      throw FileError(path, "a point has a non-finite coordinate");
  if (m.tris.empty()) throw FileError(path, "no triangles (no polygon with three or more corners)");
  if (counts) *counts = c;
  return m;
}

namespace {

void check_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw FileError(path, "no such file");
  if (fs::is_directory(path, ec)) throw FileError(path, "is a directory, not a surface file");
  if (!std::ifstream(path, std::ios::binary)) throw FileError(path, "cannot open file");
  if (fs::file_size(path, ec) == 0) throw FileError(path, "empty file");
}

TriangleMesh read_off_surface(const std::string& path, SurfaceReadCounts* counts) {
  using P = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<P> points;
  std::vector<std::vector<size_t>> polys;
  std::ifstream in(path);
  if (!CGAL::IO::read_OFF(in, points, polys, CGAL::parameters::verbose(false)))
    throw FileError(path, "not a valid OFF surface (CGAL's reader stopped; check the counts and the face lines)");
  auto vp = vtkSmartPointer<vtkPoints>::New();
  vp->SetDataTypeToDouble();
  vp->SetNumberOfPoints(vtkIdType(points.size()));
  for (size_t i = 0; i < points.size(); ++i) vp->SetPoint(vtkIdType(i), points[i].x(), points[i].y(), points[i].z());
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  std::vector<vtkIdType> ids;
  for (size_t f = 0; f < polys.size(); ++f) {
    ids.clear();
    for (size_t v : polys[f]) {
      if (v >= points.size())
        throw FileError(path, "face " + std::to_string(f) + " names point " + std::to_string(v) + " of " +
                                  std::to_string(points.size()));
      ids.push_back(vtkIdType(v));
    }
    cells->InsertNextCell(vtkIdType(ids.size()), ids.data());
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(vp);
  pd->SetPolys(cells);
  return triangles_of_polydata(pd, path, counts);
}

template <class Reader>
TriangleMesh read_with(const std::string& path, SurfaceReadCounts* counts) {
  detail::VtkMessageCapture capture;
  auto r = vtkSmartPointer<Reader>::New();
  capture.watch(r);
  r->SetFileName(path.c_str());
  r->Update();
  if (capture.has_error()) throw FileError(path, capture.first_error());
  vtkPolyData* pd = r->GetOutput();
  if (!pd || pd->GetNumberOfPoints() == 0) throw FileError(path, "no points (not a valid " + lower_extension(path).substr(1) + " file?)");
  // VTK's readers keep out-of-range indices as they are; refuse them here.
  const vtkIdType np = pd->GetNumberOfPoints();
  if (vtkCellArray* polys = pd->GetPolys()) {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType k = 0; k < n; ++k)
        if (ids[k] < 0 || ids[k] >= np)
          throw FileError(path, "face " + std::to_string(it->GetCurrentCellId()) + " names point " +
                                    std::to_string(ids[k]) + " of " + std::to_string(np));
    }
  }
  return triangles_of_polydata(pd, path, counts);
}

}  // namespace

TriangleMesh read_surface(const std::string& path, SurfaceReadCounts* counts) {
  check_file(path);
  const std::string e = lower_extension(path);
  if (e == ".obj") return read_with<vtkOBJReader>(path, counts);
  if (e == ".ply") return read_with<vtkPLYReader>(path, counts);
  if (e == ".stl") return read_with<vtkSTLReader>(path, counts);
  if (e == ".off") {
    if (!off_keyword(first_token(path)))
      throw FileError(path, 1, "not an OFF surface (no OFF keyword on the first line; a classic tet .off is a volume mesh)");
    return read_off_surface(path, counts);
  }
  throw FileError(path, "unknown surface format (expected .obj, .ply, .stl or .off with the OFF keyword)");
}

}  // namespace zs
