#include "geometry/tets/io/vtk_tet_grid.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include "base/util/file_error.h"

namespace zs {

vtkSmartPointer<vtkUnstructuredGrid> vtk_tet_grid(const TetMesh& m, const std::string& path) {
  if (!m.scalars.empty() && m.scalars.size() != m.points.size())
    throw FileError(path, "cannot write: " + std::to_string(m.scalars.size()) + " scalars for " +
                              std::to_string(m.points.size()) + " points");
  if (m.has_cell_scalars() && m.cell_scalars.size() != m.tets.size())
    throw FileError(path, "cannot write: " + std::to_string(m.cell_scalars.size()) + " cell scalars for " +
                              std::to_string(m.tets.size()) + " tets");

  // Double points so a write/read round trip is bit-exact.
  auto pts = vtkSmartPointer<vtkPoints>::New();
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(m.points.size()));
  for (size_t i = 0; i < m.points.size(); ++i)
    pts->SetPoint(static_cast<vtkIdType>(i), m.points[i].x, m.points[i].y, m.points[i].z);

  // Build the connectivity arrays directly: far cheaper than InsertNextCell.
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  auto conn = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfValues(static_cast<vtkIdType>(m.tets.size() + 1));
  conn->SetNumberOfValues(static_cast<vtkIdType>(4 * m.tets.size()));
  for (size_t t = 0; t < m.tets.size(); ++t) {
    offsets->SetValue(static_cast<vtkIdType>(t), static_cast<vtkIdType>(4 * t));
    for (int k = 0; k < 4; ++k) {
      if (m.tets[t][k] >= m.points.size())
        throw FileError(path, "cannot write: tet " + std::to_string(t) + " references point " +
                                  std::to_string(m.tets[t][k]) + " (only " +
                                  std::to_string(m.points.size()) + " points)");
      conn->SetValue(static_cast<vtkIdType>(4 * t + k), m.tets[t][k]);
    }
  }
  offsets->SetValue(static_cast<vtkIdType>(m.tets.size()),
                    static_cast<vtkIdType>(4 * m.tets.size()));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, conn);

  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(pts);
  grid->SetCells(VTK_TETRA, cells);

  const std::vector<double>& values = m.scalar_values();
  if (!values.empty()) {
    auto arr = vtkSmartPointer<vtkDoubleArray>::New();
    arr->SetName(m.scalar_name.empty() ? "scalar" : m.scalar_name.c_str());
    arr->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
    for (size_t i = 0; i < values.size(); ++i) arr->SetValue(static_cast<vtkIdType>(i), values[i]);
    if (m.has_cell_scalars()) grid->GetCellData()->SetScalars(arr);
    else grid->GetPointData()->SetScalars(arr);
  }
  return grid;
}

}  // namespace zs
