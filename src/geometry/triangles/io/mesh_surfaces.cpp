#include "geometry/triangles/io/mesh_surfaces.h"

#include <vtkCellDataToPointData.h>
#include <vtkContourFilter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "base/util/file_error.h"
#include "geometry/tets/io/vtk_capture.h"
#include "geometry/tets/io/vtk_tet_grid.h"
#include "geometry/tets/topology.h"
#include "geometry/triangles/io/polydata_triangles.h"

namespace zs {

TriangleMesh boundary_surface(const TetMesh& m, const std::string& name) {
  // The topology's boundary faces, each wound outward (away from its tet's
  // fourth vertex). Not vtkGeometryFilter: VTK 9.1's leaks under ASan, and
  // the faces are already known here.
  const Topology topo = build_topology(m);
  TriangleMesh t;
  t.points = m.points;
  for (uint32_t f = 0; f < topo.num_faces(); ++f) {
    if (topo.tet1(f) != kNoTet || topo.tet_degenerate[topo.tet0(f)]) continue;
    const auto fv = topo.face(f);
    uint32_t opp = m.tets[topo.tet0(f)][0];
    for (uint32_t v : m.tets[topo.tet0(f)])
      if (v != fv[0] && v != fv[1] && v != fv[2]) opp = v;
    const glm::dvec3 a = m.points[fv[0]];
    const bool inward = glm::dot(glm::cross(m.points[fv[1]] - a, m.points[fv[2]] - a), m.points[opp] - a) > 0;
    t.tris.push_back(inward ? std::array<uint32_t, 3>{fv[0], fv[2], fv[1]} : std::array<uint32_t, 3>{fv[0], fv[1], fv[2]});
  }
  if (t.tris.empty()) throw FileError(name, "the mesh has no boundary faces");
  t.surface.assign(t.tris.size(), 0);
  return t;
}

TriangleMesh isosurfaces(const TetMesh& m, const std::vector<double>& values, const std::string& name) {
  if (m.scalar_values().empty()) throw FileError(name, "an isosurface needs a scalar, and the mesh has none");
  detail::VtkMessageCapture capture;
  vtkSmartPointer<vtkDataSet> input = vtk_tet_grid(m, name);
  if (m.has_cell_scalars()) {
    auto c2p = vtkSmartPointer<vtkCellDataToPointData>::New();
    capture.watch(c2p);
    c2p->SetInputData(input);
    c2p->Update();
    input = c2p->GetOutput();
  }
  auto f = vtkSmartPointer<vtkContourFilter>::New();
  capture.watch(f);
  f->SetInputData(input);
  f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
                            m.scalar_name.empty() ? "scalar" : m.scalar_name.c_str());
  f->SetNumberOfContours(int(values.size()));
  for (size_t i = 0; i < values.size(); ++i) f->SetValue(int(i), values[i]);
  f->ComputeNormalsOff();
  f->ComputeScalarsOff();
  f->Update();
  if (capture.has_error()) throw FileError(name, "cannot contour the scalar: " + capture.first_error());
  char what[160];
  if (f->GetOutput()->GetNumberOfPolys() == 0) {
    double lo = INFINITY, hi = -INFINITY;
    for (double v : m.scalar_values())
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    std::snprintf(what, sizeof what, "no isosurface: the scalar '%s' (range [%.9g, %.9g]) takes none of the values",
                  m.scalar_name.c_str(), lo, hi);
    throw FileError(name, what);
  }
  std::snprintf(what, sizeof what, " (isosurface%s %.6g%s)", values.size() > 1 ? "s from" : "", values.front(),
                values.size() > 1 ? ", ..." : "");
  return triangles_of_polydata(f->GetOutput(), name + what, nullptr);
}

}  // namespace zs
