// read_vtk: any dataset VTK can read from .vtu / legacy .vtk -> linear tets.
//
// Pipeline: read -> pick one scalar (point data, or cell data kept per cell
// unless averaged onto the points; vtk_scalar.h) -> reduce higher-order 3-D
// cells to their corner nodes -> split non-tet 3-D cells with
// vtkDataSetTriangleFilter (each tet keeps its cell's value) -> drop points
// no tet uses.
#include <vtkCell.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkCellData.h>
#include <vtkCellDataToPointData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkGenericCell.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredGrid.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <algorithm>
#include <climits>
#include <stdexcept>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "geometry/tets/io/vtk_capture.h"
#include "base/util/file_name.h"
#include "geometry/tets/io/vtk_scalar.h"
#include "geometry/tets/io/vtk_io.h"
#include "base/util/file_error.h"

namespace zs {

namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- reading

vtkSmartPointer<vtkDataSet> read_dataset(const std::string& path,
                                         detail::VtkMessageCapture& capture) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw FileError(path, "no such file");
  if (fs::is_directory(path, ec)) throw FileError(path, "is a directory, not a mesh file");
  if (!std::ifstream(path, std::ios::binary)) throw FileError(path, "cannot open file");
  if (fs::file_size(path, ec) == 0) throw FileError(path, "empty file");

  // Cheap signature checks first: VTK's own complaint about a random file
  // echoes its bytes back.
  std::string head(64, '\0');
  {
    std::ifstream f(path, std::ios::binary);
    f.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<size_t>(f.gcount()));
  }
  const bool legacy = lower_extension(path) == ".vtk";
  std::string lower = head.substr(0, 14);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (legacy && lower != "# vtk datafile")  // VTK compares case-insensitively too
    throw FileError(path, "not a legacy VTK file (no '# vtk DataFile' header)");
  const auto first = head.find_first_not_of(" \t\r\n\xEF\xBB\xBF");  // BOM too
  if (!legacy && (first == std::string::npos || head[first] != '<'))
    throw FileError(path, "not a VTK XML file");

  vtkSmartPointer<vtkDataObject> out;
  if (legacy) {
    auto r = vtkSmartPointer<vtkGenericDataObjectReader>::New();
    capture.watch(r);
    r->SetFileName(path.c_str());
    // By default the legacy reader keeps only the first array per attribute
    // type; we want every array so opt.scalar can name any of them.
    r->ReadAllScalarsOn();
    r->ReadAllVectorsOn();
    r->ReadAllTensorsOn();
    r->ReadAllNormalsOn();
    r->ReadAllFieldsOn();
    r->ReadAllColorScalarsOn();
    r->ReadAllTCoordsOn();
    r->Update();
    out = r->GetOutput();
  } else {
    auto r = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    capture.watch(r);
    r->SetFileName(path.c_str());
    r->Update();
    out = r->GetOutput();
  }
  if (capture.has_error()) throw FileError(path, "VTK reader: " + capture.first_error());
  // The legacy reader only warns on short data and keeps what it read.
  const std::string warning = capture.first_warning();
  if (!warning.empty()) throw FileError(path, "VTK reader: " + warning);
  if (!out) throw FileError(path, "not a readable VTK file");
  auto* ds = vtkDataSet::SafeDownCast(out);
  if (!ds)
    throw FileError(path, std::string("unsupported VTK data type ") + out->GetClassName() +
                              " (expected a single dataset)");
  if (ds->GetNumberOfPoints() == 0 || ds->GetNumberOfCells() == 0)
    throw FileError(path, "no cells (empty or unreadable VTK file)");
  return ds;
}

// ---------------------------------------------------------------- cells

// For a higher-order 3-D cell: the linear cell on its corner nodes (which VTK
// always stores first) and how many corners; {-1, 0} if not higher order.
std::pair<int, int> corner_cell(int type) {
  switch (type) {
    case VTK_QUADRATIC_TETRA:
    case VTK_HIGHER_ORDER_TETRAHEDRON:
    case VTK_LAGRANGE_TETRAHEDRON:
    case VTK_BEZIER_TETRAHEDRON:
      return {VTK_TETRA, 4};
    case VTK_QUADRATIC_HEXAHEDRON:
    case VTK_TRIQUADRATIC_HEXAHEDRON:
    case VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON:
    case VTK_HIGHER_ORDER_HEXAHEDRON:
    case VTK_LAGRANGE_HEXAHEDRON:
    case VTK_BEZIER_HEXAHEDRON:
      return {VTK_HEXAHEDRON, 8};
    case VTK_QUADRATIC_WEDGE:
    case VTK_QUADRATIC_LINEAR_WEDGE:
    case VTK_BIQUADRATIC_QUADRATIC_WEDGE:
    case VTK_HIGHER_ORDER_WEDGE:
    case VTK_LAGRANGE_WEDGE:
    case VTK_BEZIER_WEDGE:
      return {VTK_WEDGE, 6};
    case VTK_QUADRATIC_PYRAMID:
    case VTK_TRIQUADRATIC_PYRAMID:
    case VTK_HIGHER_ORDER_PYRAMID:
    case VTK_LAGRANGE_PYRAMID:
    case VTK_BEZIER_PYRAMID:
      return {VTK_PYRAMID, 5};
    default:
      return {-1, 0};
  }
}

// Topological dimension of a cell type, cached (VTK 9.1 has no static query).
int cell_dimension(int type, std::map<int, int>& cache) {
  auto it = cache.find(type);
  if (it != cache.end()) return it->second;
  int dim = -1;
  if (type != VTK_EMPTY_CELL) {
    vtkCell* c = vtkGenericCell::InstantiateCell(type);
    if (c) {
      dim = c->GetCellDimension();
      c->Delete();
    }
  }
  cache[type] = dim;
  return dim;
}

// Splits the cells of ug (already linear, sharing ds's point ids) into tets
// with vtkDataSetTriangleFilter; ids map back through an id array so we do
// not depend on the filter keeping point order. With `origin`, each tet's
// cell id in `cell_ids` (the dataset's own numbering; the filter copies cell
// data to the tets it makes) is appended to it.
void triangulate(vtkDataSet* in, std::vector<Tet>& tets, const std::string& path,
                 detail::VtkMessageCapture& capture, const std::vector<vtkIdType>* cell_ids = nullptr,
                 std::vector<vtkIdType>* origin = nullptr) {
  auto ids = vtkSmartPointer<vtkIdTypeArray>::New();
  ids->SetName("zs_original_id");
  ids->SetNumberOfValues(in->GetNumberOfPoints());
  for (vtkIdType i = 0; i < in->GetNumberOfPoints(); ++i) ids->SetValue(i, i);
  in->GetPointData()->AddArray(ids);
  if (origin) {
    auto cids = vtkSmartPointer<vtkIdTypeArray>::New();
    cids->SetName("zs_original_cell");
    cids->SetNumberOfValues(in->GetNumberOfCells());
    for (vtkIdType i = 0; i < in->GetNumberOfCells(); ++i) cids->SetValue(i, cell_ids ? (*cell_ids)[size_t(i)] : i);
    in->GetCellData()->AddArray(cids);
  }

  auto tf = vtkSmartPointer<vtkDataSetTriangleFilter>::New();
  capture.watch(tf);
  tf->SetInputData(in);
  tf->TetrahedraOnlyOn();
  tf->Update();
  vtkUnstructuredGrid* out = tf->GetOutput();
  in->GetPointData()->RemoveArray("zs_original_id");
  if (origin) in->GetCellData()->RemoveArray("zs_original_cell");
  if (capture.has_error() || !out)
    throw FileError(path, "cannot split cells into tets: " + capture.first_error());
  auto* back = vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("zs_original_id"));
  if (!back) throw FileError(path, "cannot split cells into tets: point ids lost");
  auto* cell_back = origin ? vtkIdTypeArray::SafeDownCast(out->GetCellData()->GetArray("zs_original_cell")) : nullptr;
  if (origin && !cell_back) throw FileError(path, "cannot split cells into tets: cell ids lost");
  auto idlist = vtkSmartPointer<vtkIdList>::New();
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c) {
    if (out->GetCellType(c) != VTK_TETRA) continue;
    out->GetCellPoints(c, idlist);
    Tet t;
    for (int k = 0; k < 4; ++k) t[k] = static_cast<uint32_t>(back->GetValue(idlist->GetId(k)));
    tets.push_back(t);
    if (origin) origin->push_back(cell_back->GetValue(c));
  }
}

std::string plural(size_t n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

// Cells of an unstructured-like dataset -> tets on ds's point ids; with
// `origin`, each tet's cell id.
std::vector<Tet> tets_of_cells(vtkDataSet* ds, TetMesh& m, const std::string& path,
                               detail::VtkMessageCapture& capture, std::vector<vtkIdType>* origin) {
  std::vector<Tet> tets;
  std::vector<vtkIdType> lin_cells;  // the cell id of each cell of `lin`
  std::map<int, int> dim_cache;
  std::map<int, size_t> reduced, split, dropped;  // by original cell type
  auto lin = vtkSmartPointer<vtkUnstructuredGrid>::New();
  auto* ps = vtkPointSet::SafeDownCast(ds);
  if (ps && ps->GetPoints()) {
    lin->SetPoints(ps->GetPoints());
  } else {
    auto pts = vtkSmartPointer<vtkPoints>::New();
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(ds->GetNumberOfPoints());
    for (vtkIdType i = 0; i < ds->GetNumberOfPoints(); ++i) pts->SetPoint(i, ds->GetPoint(i));
    lin->SetPoints(pts);
  }
  auto* ug = vtkUnstructuredGrid::SafeDownCast(ds);
  auto idl = vtkSmartPointer<vtkIdList>::New();
  const vtkIdType npts = ds->GetNumberOfPoints();
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c) {
    const int type = ds->GetCellType(c);
    if (type == VTK_POLYHEDRON && ug) {
      ug->GetFaceStream(c, idl);  // polyhedra need their faces, not just points
      lin->InsertNextCell(VTK_POLYHEDRON, idl);
      if (origin) lin_cells.push_back(c);
      ++split[type];
      continue;
    }
    ds->GetCellPoints(c, idl);
    for (vtkIdType k = 0; k < idl->GetNumberOfIds(); ++k)
      if (idl->GetId(k) < 0 || idl->GetId(k) >= npts)
        throw FileError(path, "cell " + std::to_string(c) + " references point " +
                                  std::to_string(idl->GetId(k)) + " of " + std::to_string(npts));
    auto [lt, nc] = corner_cell(type);
    int linear = type;
    if (lt >= 0) {
      if (idl->GetNumberOfIds() < nc)
        throw FileError(path, "cell " + std::to_string(c) + " has too few points");
      idl->SetNumberOfIds(nc);
      linear = lt;
      ++reduced[type];
    }
    if (linear == VTK_TETRA) {
      if (idl->GetNumberOfIds() != 4)
        throw FileError(path, "tetra " + std::to_string(c) + " without 4 points");
      tets.push_back({static_cast<uint32_t>(idl->GetId(0)), static_cast<uint32_t>(idl->GetId(1)),
                      static_cast<uint32_t>(idl->GetId(2)), static_cast<uint32_t>(idl->GetId(3))});
      if (origin) origin->push_back(c);
      continue;
    }
    if (cell_dimension(linear, dim_cache) != 3) {
      ++dropped[type];
      continue;
    }
    lin->InsertNextCell(linear, idl);
    if (origin) lin_cells.push_back(c);
    ++split[type];
  }
  auto cells = [](size_t n, int type) {
    const char* name = vtkCellTypes::GetClassNameFromTypeId(type);
    return std::to_string(n) + " " + (name ? name : "unknown") + (n == 1 ? " cell" : " cells") +
           " (VTK type " + std::to_string(type) + ")";
  };
  for (auto [t, n] : reduced) m.notes.push_back(cells(n, t) + " reduced to their corner nodes");
  for (auto [t, n] : dropped) m.notes.push_back("dropped " + cells(n, t) + ": not 3-D");
  if (lin->GetNumberOfCells() > 0) {
    const size_t before = tets.size();
    triangulate(lin, tets, path, capture, &lin_cells, origin);
    size_t nsplit = 0;
    for (auto [t, n] : split) nsplit += n;
    m.notes.push_back("split " + plural(nsplit, "non-tet 3-D cell") + " into " +
                      plural(tets.size() - before, "tet") + " (vtkDataSetTriangleFilter)");
  }
  return tets;
}

// Image data / structured / rectilinear grids: the filter's structured path
// splits each hex into 5 tets with alternating parity (conforming).
std::vector<Tet> tets_of_structured(vtkDataSet* ds, TetMesh& m, const std::string& path,
                                    detail::VtkMessageCapture& capture, std::vector<vtkIdType>* origin) {
  int dims[3] = {0, 0, 0};
  if (auto* im = vtkImageData::SafeDownCast(ds))
    im->GetDimensions(dims);
  else if (auto* sg = vtkStructuredGrid::SafeDownCast(ds))
    sg->GetDimensions(dims);
  else if (auto* rg = vtkRectilinearGrid::SafeDownCast(ds))
    rg->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
    throw FileError(path, "no 3-D cells (structured grid " + std::to_string(dims[0]) + "x" +
                              std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + ")");
  vtkSmartPointer<vtkDataSet> copy;
  copy.TakeReference(ds->NewInstance());
  copy->ShallowCopy(ds);  // the id array goes on the copy, not the reader's output
  std::vector<Tet> tets;
  triangulate(copy, tets, path, capture, nullptr, origin);
  m.notes.push_back(std::string(ds->GetClassName()) + " " + std::to_string(dims[0]) + "x" +
                    std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + ": " +
                    plural(static_cast<size_t>(ds->GetNumberOfCells()), "cell") + " split into " +
                    plural(tets.size(), "tet") + " (vtkDataSetTriangleFilter, not thresholded)");
  return tets;
}

}  // namespace

namespace {

// The tets of a dataset (read_vtk's pipeline after reading).
TetMesh tet_mesh_of(vtkDataSet* ds, const ReadOptions& opt, const std::string& path,
                    detail::VtkMessageCapture& capture) {
  if (ds->GetNumberOfPoints() >= static_cast<vtkIdType>(UINT32_MAX))
    throw FileError(path, "too many points for 32-bit tet indices");
  TetMesh m;
  detail::PickedScalar picked = detail::pick_scalar(ds, opt, path, m, capture);
  std::vector<double> scal = picked.cell ? std::vector<double>() : std::move(picked.values);
  const bool structured = vtkImageData::SafeDownCast(ds) || vtkStructuredGrid::SafeDownCast(ds) ||
                          vtkRectilinearGrid::SafeDownCast(ds);
  std::vector<vtkIdType> origin;  // cell data: each tet's cell
  std::vector<vtkIdType>* want_origin = picked.cell ? &origin : nullptr;
  std::vector<Tet> tets = structured ? tets_of_structured(ds, m, path, capture, want_origin)
                                     : tets_of_cells(ds, m, path, capture, want_origin);
  if (tets.empty()) throw FileError(path, "no 3-D cells to make tets from");
  if (picked.cell) {
    if (origin.size() != tets.size()) throw FileError(path, "cannot split cells into tets: cell ids lost");
    m.cell_scalars.resize(tets.size());
    for (size_t t = 0; t < tets.size(); ++t) {
      const vtkIdType c = origin[t];
      if (c < 0 || size_t(c) >= picked.values.size()) throw FileError(path, "cannot split cells into tets: cell ids lost");
      m.cell_scalars[t] = picked.values[size_t(c)];
    }
  }

  // Keep only points some tet uses (e.g. quadratic mid-edge nodes go).
  const auto n = static_cast<size_t>(ds->GetNumberOfPoints());
  std::vector<uint32_t> remap(n, UINT32_MAX);
  for (const Tet& t : tets)
    for (uint32_t v : t) remap[v] = 0;
  uint32_t next = 0;
  for (auto& r : remap)
    if (r == 0) r = next++;
  m.points.reserve(next);
  if (!scal.empty()) m.scalars.reserve(next);
  double p[3];
  for (size_t i = 0; i < n; ++i) {
    if (remap[i] == UINT32_MAX) continue;
    ds->GetPoint(static_cast<vtkIdType>(i), p);
    m.points.emplace_back(p[0], p[1], p[2]);
    if (!scal.empty()) m.scalars.push_back(scal[i]);
  }
  for (Tet& t : tets)
    for (uint32_t& v : t) v = remap[v];
  m.tets = std::move(tets);
  if (next < n) m.notes.push_back("dropped " + plural(n - next, "point") + " used by no tet");
  return m;
}

}  // namespace

TetMesh read_vtk(const std::string& path, const ReadOptions& opt) {
  detail::VtkMessageCapture capture;
  vtkSmartPointer<vtkDataSet> ds = read_dataset(path, capture);
  return tet_mesh_of(ds, opt, path, capture);
}

namespace {

// Points a cell of this type has: > 0 exactly that many, 0 any number (at
// least one), -n at least n (higher-order cells), INT_MIN not a type we take.
// VTK trusts a grid's arrays; arrays from a caller are checked against this
// first, so no cell makes VTK read past its connectivity.
int cell_points(int type) {
  switch (type) {
    case VTK_VERTEX: return 1;
    case VTK_LINE: return 2;
    case VTK_TRIANGLE: return 3;
    case VTK_PIXEL: case VTK_QUAD: case VTK_TETRA: return 4;
    case VTK_PYRAMID: return 5;
    case VTK_WEDGE: return 6;
    case VTK_VOXEL: case VTK_HEXAHEDRON: return 8;
    case VTK_PENTAGONAL_PRISM: return 10;
    case VTK_HEXAGONAL_PRISM: return 12;
    case VTK_QUADRATIC_EDGE: return 3;
    case VTK_QUADRATIC_TRIANGLE: return 6;
    case VTK_QUADRATIC_QUAD: return 8;
    case VTK_QUADRATIC_TETRA: return 10;
    case VTK_QUADRATIC_HEXAHEDRON: return 20;
    case VTK_QUADRATIC_WEDGE: return 15;
    case VTK_QUADRATIC_PYRAMID: return 13;
    case VTK_BIQUADRATIC_QUAD: return 9;
    case VTK_TRIQUADRATIC_HEXAHEDRON: return 27;
    case VTK_TRIQUADRATIC_PYRAMID: return 19;
    case VTK_QUADRATIC_LINEAR_QUAD: return 6;
    case VTK_QUADRATIC_LINEAR_WEDGE: return 12;
    case VTK_BIQUADRATIC_QUADRATIC_WEDGE: return 18;
    case VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON: return 24;
    case VTK_BIQUADRATIC_TRIANGLE: return 7;
    case VTK_CUBIC_LINE: return 4;
    case VTK_POLY_VERTEX: case VTK_POLY_LINE: return 0;
    case VTK_TRIANGLE_STRIP: case VTK_POLYGON: return -3;
    default: {
      const auto corner = corner_cell(type);
      return corner.first >= 0 ? -corner.second : INT_MIN;
    }
  }
}

}  // namespace

TetMesh tet_mesh_from_cells(const VtkCells& c, const std::string& name) {
  static_assert(sizeof(vtkIdType) == sizeof(int64_t), "VTK built with 64-bit ids");
  for (int64_t i = 0; i < c.num_cells; ++i) {
    const int want = cell_points(int(c.types[i]));
    const int64_t have = c.offsets[i + 1] - c.offsets[i];
    if (want == INT_MIN)
      throw std::runtime_error(name + ": cell " + std::to_string(i) + " has VTK type " + std::to_string(c.types[i]) +
                               ", which is not taken from arrays");
    if ((want > 0 && have != want) || (want == 0 && have < 1) || (want < 0 && have < -want))
      throw std::runtime_error(name + ": cell " + std::to_string(i) + " (VTK type " + std::to_string(c.types[i]) +
                               ") has " + std::to_string(have) + " points");
  }
  detail::VtkMessageCapture capture;
  auto xyz = vtkSmartPointer<vtkDoubleArray>::New();
  xyz->SetNumberOfComponents(3);
  xyz->SetArray(const_cast<double*>(c.points), c.num_points * 3, 1);  // 1: VTK never frees it
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(xyz);
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetArray(reinterpret_cast<vtkIdType*>(const_cast<int64_t*>(c.offsets)), c.num_cells + 1, 1);
  auto conn = vtkSmartPointer<vtkIdTypeArray>::New();
  conn->SetArray(reinterpret_cast<vtkIdType*>(const_cast<int64_t*>(c.connectivity)), c.num_connectivity, 1);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, conn);
  auto types = vtkSmartPointer<vtkUnsignedCharArray>::New();
  types->SetNumberOfValues(c.num_cells);
  for (int64_t i = 0; i < c.num_cells; ++i) types->SetValue(i, static_cast<unsigned char>(c.types[i]));
  auto ug = vtkSmartPointer<vtkUnstructuredGrid>::New();
  ug->SetPoints(points);
  ug->SetCells(types, cells);
  ReadOptions opt;
  opt.association = c.association;
  if (c.scalars) {
    auto s = vtkSmartPointer<vtkDoubleArray>::New();
    s->SetName("scalar");
    s->SetArray(const_cast<double*>(c.scalars), c.num_points, 1);
    ug->GetPointData()->SetScalars(s);
    opt.scalar = "scalar";
  } else if (c.cell_scalars) {
    // The averaging rounds in the array's own type (vtkCellDataToPointData).
    vtkSmartPointer<vtkDataArray> s;
    if (c.cell_scalars_float) {
      auto f = vtkSmartPointer<vtkFloatArray>::New();
      f->SetNumberOfValues(c.num_cells);
      for (int64_t i = 0; i < c.num_cells; ++i) f->SetValue(i, float(c.cell_scalars[i]));
      s = f;
    } else {
      auto d = vtkSmartPointer<vtkDoubleArray>::New();
      d->SetArray(const_cast<double*>(c.cell_scalars), c.num_cells, 1);
      s = d;
    }
    s->SetName("scalar");
    ug->GetCellData()->SetScalars(s);
    opt.scalar = "scalar";
  }
  return tet_mesh_of(ug, opt, name, capture);
}

}  // namespace zs
