// Which scalar a VTK dataset gives a tet mesh: the named array (point data
// first, then cell data), else the active point scalar or the first array,
// among the arrays the association allows; a constant default gives way to
// the first array that varies. Cell data stay per cell (one value per tet)
// unless the association asks for them averaged onto the points.
#include "geometry/tets/io/vtk_scalar.h"

#include <vtkCellData.h>
#include <vtkCellDataToPointData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDataSetAttributes.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/util/file_error.h"

namespace zs::detail {

namespace {

bool usable(vtkDataArray* a) {
  return a && a->GetName() && std::string(a->GetName()) != vtkDataSetAttributes::GhostArrayName() &&
         a->GetNumberOfComponents() > 0;
}

std::string array_list(vtkDataSet* ds) {
  std::string s;
  auto add = [&](vtkDataSetAttributes* attrs, const char* where) {
    for (int i = 0; i < attrs->GetNumberOfArrays(); ++i) {
      vtkDataArray* a = attrs->GetArray(i);
      if (!usable(a)) continue;
      s += (s.empty() ? "" : ", ") + std::string(a->GetName()) + " (" + where + ")";
    }
  };
  add(ds->GetPointData(), "point");
  add(ds->GetCellData(), "cell");
  return s.empty() ? "none" : s;
}

// The finite range of an array's values (its magnitude, for vectors); lo > hi
// when it has no finite value.
void value_range(vtkDataArray* a, double* lo, double* hi) {
  *lo = INFINITY, *hi = -INFINITY;
  const int nc = a->GetNumberOfComponents();
  std::vector<double> t(static_cast<size_t>(nc));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
    double v;
    if (nc == 1) {
      v = a->GetComponent(i, 0);
    } else {
      a->GetTuple(i, t.data());
      double q = 0;
      for (double x : t) q += x * x;
      v = std::sqrt(q);
    }
    if (std::isfinite(v)) *lo = std::min(*lo, v), *hi = std::max(*hi, v);
  }
}

bool varies(vtkDataArray* a) {
  double lo, hi;
  value_range(a, &lo, &hi);
  return lo < hi;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

vtkDataArray* first_usable(vtkDataSetAttributes* attrs) {
  if (usable(attrs->GetScalars())) return attrs->GetScalars();
  for (int i = 0; i < attrs->GetNumberOfArrays(); ++i)
    if (usable(attrs->GetArray(i))) return attrs->GetArray(i);
  return nullptr;
}

// Averages one cell array onto the points (each point: mean of the cells
// that use it) and returns the resulting point array.
vtkSmartPointer<vtkDataArray> cell_to_point(vtkDataSet* ds, const std::string& name,
                                            const std::string& path,
                                            detail::VtkMessageCapture& capture) {
  auto c2p = vtkSmartPointer<vtkCellDataToPointData>::New();
  capture.watch(c2p);
  c2p->SetInputData(ds);
  c2p->ProcessAllArraysOff();
  c2p->AddCellDataArray(name.c_str());
  c2p->PassCellDataOff();
  c2p->Update();
  vtkDataArray* a =
      c2p->GetOutput() ? c2p->GetOutput()->GetPointData()->GetArray(name.c_str()) : nullptr;
  if (!a || capture.has_error())
    throw FileError(path, "cannot average cell data '" + name + "' onto points" +
                              (capture.has_error() ? ": " + capture.first_error() : ""));
  return a;
}

}  // namespace

// Picks the scalar per opt.scalar, opt.association and the defaults.
PickedScalar pick_scalar(vtkDataSet* ds, const ReadOptions& opt, const std::string& path, TetMesh& m,
                         detail::VtkMessageCapture& capture) {
  const bool points_ok = opt.association != ScalarAssociation::Cell;
  const bool cells_ok = opt.association != ScalarAssociation::Point;
  vtkDataArray* pa = nullptr;
  vtkDataArray* ca = nullptr;
  if (!opt.scalar.empty()) {
    vtkDataArray* p = ds->GetPointData()->GetArray(opt.scalar.c_str());
    vtkDataArray* c = ds->GetCellData()->GetArray(opt.scalar.c_str());
    if (points_ok && usable(p)) pa = p;
    else if (cells_ok && usable(c)) ca = c;
    else if (usable(p) || usable(c))
      throw FileError(path, "array '" + opt.scalar + "' is " + (usable(p) ? "point" : "cell") +
                                " data, and association is '" + to_string(opt.association) + "'");
    else
      throw FileError(path, "no array named '" + opt.scalar + "'; available: " + array_list(ds));
  } else {
    if (points_ok) pa = first_usable(ds->GetPointData());
    if (!pa && cells_ok) ca = first_usable(ds->GetCellData());
    // A constant default (a uniform field): the first array that varies,
    // point data before cell data, so the default render shows something.
    vtkDataArray* def = pa ? pa : ca;
    if (def && !varies(def)) {
      bool found = false;
      for (int cell = 0; cell < 2 && !found; ++cell) {
        if (!(cell ? cells_ok : points_ok)) continue;
        vtkDataSetAttributes* attrs = cell ? static_cast<vtkDataSetAttributes*>(ds->GetCellData())
                                           : static_cast<vtkDataSetAttributes*>(ds->GetPointData());
        for (int i = 0; i < attrs->GetNumberOfArrays() && !found; ++i) {
          vtkDataArray* a = attrs->GetArray(i);
          if (!usable(a) || !varies(a)) continue;
          double lo, hi;
          value_range(def, &lo, &hi);
          m.scalar_choice = "'" + std::string(def->GetName()) + "' is constant (" + (lo <= hi ? num(lo) : "no finite value") + ")";
          pa = cell ? nullptr : a;
          ca = cell ? a : nullptr;
          found = true;
        }
      }
    }
  }
  if (!pa && !ca) {
    if (opt.association == ScalarAssociation::Point || opt.association == ScalarAssociation::Cell) {
      if (first_usable(ds->GetPointData()) || first_usable(ds->GetCellData()))
        throw FileError(path, std::string("no ") + to_string(opt.association) + " data array (association is '" +
                                  to_string(opt.association) + "'); available: " + array_list(ds));
    }
    m.notes.push_back("no point or cell data arrays: mesh has no scalar");
    return {};
  }
  PickedScalar out;
  vtkSmartPointer<vtkDataArray> arr = pa;
  if (ca && opt.association == ScalarAssociation::CellToPoint) {
    arr = cell_to_point(ds, ca->GetName(), path, capture);
    m.notes.push_back("scalar '" + std::string(ca->GetName()) +
                      "' is cell data: averaged onto points (vtkCellDataToPointData)");
  } else if (ca) {
    arr = ca;
    out.cell = true;
    m.notes.push_back("scalar '" + std::string(ca->GetName()) +
                      "' is cell data: one value per tet (each tet keeps its cell's value)");
  }
  m.scalar_name = arr->GetName();
  if (!m.scalar_choice.empty())
    m.notes.push_back("scalar '" + m.scalar_name + "', the first array that varies: " + m.scalar_choice);
  const int nc = arr->GetNumberOfComponents();
  if (nc > 1)
    m.notes.push_back("array '" + m.scalar_name + "' has " + std::to_string(nc) +
                      " components: using its magnitude");
  const vtkIdType n = arr->GetNumberOfTuples();
  const vtkIdType want = out.cell ? ds->GetNumberOfCells() : ds->GetNumberOfPoints();
  if (n < want)
    throw FileError(path, "array '" + m.scalar_name + "' has " + std::to_string(n) + " values for " +
                              std::to_string(want) + (out.cell ? " cells" : " points"));
  out.values.resize(static_cast<size_t>(want));
  std::vector<double> tuple(static_cast<size_t>(nc));
  for (vtkIdType i = 0; i < want; ++i) {
    if (nc == 1) {
      out.values[static_cast<size_t>(i)] = arr->GetComponent(i, 0);
      continue;
    }
    arr->GetTuple(i, tuple.data());
    double q = 0;
    for (double v : tuple) q += v * v;
    out.values[static_cast<size_t>(i)] = std::sqrt(q);
  }
  return out;
}

}  // namespace zs::detail
