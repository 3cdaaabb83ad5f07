#include "python/py_data.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include <pybind11/numpy.h>

#include "geometry/tets/io/vtk_io.h"


namespace zs::python {

namespace {

template <class T>
using Array = pybind11::array_t<T, pybind11::array::c_style | pybind11::array::forcecast>;

[[noreturn]] void bad(const std::string& where, const std::string& what) {
  throw pybind11::value_error(where + ": " + what);
}

pybind11::object get(const pybind11::dict& d, const char* key, const std::string& where, bool required) {
  if (d.contains(key)) return d[key];
  if (required) bad(where, std::string("missing array '") + key + "'");
  return pybind11::none();
}

// A float array of shape (n, cols) (cols 0: shape (n,)); every value finite.
Array<double> floats(const pybind11::object& o, const std::string& where, const char* name, int64_t cols,
                     int64_t rows = -1) {
  Array<double> a;
  try {
    a = Array<double>::ensure(o);
  } catch (...) {
  }
  if (!a) bad(where, std::string("'") + name + "' must be a numeric array");
  const bool ok = cols == 0 ? a.ndim() == 1 : a.ndim() == 2 && a.shape(1) == cols;
  if (!ok)
    bad(where, std::string("'") + name + "' must have shape " + (rows >= 0 ? std::to_string(rows) : "(N") +
                   (cols == 0 ? ",)" : ", " + std::to_string(cols) + ")"));
  if (rows >= 0 && a.shape(0) != rows)
    bad(where, std::string("'") + name + "' has " + std::to_string(a.shape(0)) + " rows, not " +
                   std::to_string(rows));
  const double* p = a.data();
  for (int64_t i = 0, n = int64_t(a.size()); i < n; ++i)
    if (!std::isfinite(p[i]))
      bad(where, std::string("'") + name + "' holds a non-finite value (NaN or infinity) at flat index " +
                     std::to_string(i));
  return a;
}

// An integer array of shape (n, cols) (cols 0: (n,)), each in [0, limit).
Array<int64_t> indices(const pybind11::object& o, const std::string& where, const char* name, int64_t cols,
                       int64_t limit) {
  pybind11::array raw;
  try {
    raw = pybind11::array::ensure(o);
  } catch (...) {
  }
  if (!raw || !(raw.dtype().kind() == 'i' || raw.dtype().kind() == 'u'))
    bad(where, std::string("'") + name + "' must be an integer array");
  Array<int64_t> a = Array<int64_t>::ensure(raw);
  const bool ok = cols == 0 ? a.ndim() == 1 : a.ndim() == 2 && a.shape(1) == cols;
  if (!ok)
    bad(where, std::string("'") + name + "' must have shape (M" + (cols == 0 ? ",)" : ", " + std::to_string(cols) + ")"));
  const int64_t* p = a.data();
  for (int64_t i = 0, n = int64_t(a.size()); i < n; ++i)
    if (p[i] < 0 || p[i] >= limit)
      bad(where, std::string("'") + name + "' index " + std::to_string(p[i]) + " at flat index " + std::to_string(i) +
                     " is out of range [0, " + std::to_string(limit) + ")");
  return a;
}

std::vector<glm::dvec3> points_of(const Array<double>& a) {
  std::vector<glm::dvec3> out(size_t(a.shape(0)));
  const double* p = a.data();
  for (size_t i = 0; i < out.size(); ++i) out[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
  return out;
}

}  // namespace

TetMesh tet_mesh_from(const pybind11::dict& d, const std::string& where) {
  const Array<double> pts = floats(get(d, "points", where, true), where, "points", 3);
  const int64_t n = pts.shape(0);
  if (n >= int64_t(UINT32_MAX)) bad(where, "too many points for 32-bit tet indices");
  ScalarAssociation assoc = ScalarAssociation::Auto;
  if (!get(d, "association", where, false).is_none()) {
    const pybind11::object a = d["association"];
    if (!pybind11::isinstance<pybind11::str>(a) || !parse_association(a.cast<std::string>(), &assoc))
      bad(where, "'association' must be \"auto\", \"point\", \"cell\" or \"cell_to_point\"");
  }
  if (d.contains("tets")) {
    const Array<int64_t> t = indices(d["tets"], where, "tets", 4, n);
    const int64_t nt = t.shape(0);
    TetMesh m;
    if (!get(d, "scalar", where, false).is_none()) {
      // One value per point is point data, one per tet cell data; when the
      // counts are equal, point data unless the association says cell.
      const Array<double> any = floats(d["scalar"], where, "scalar", 0);
      const bool cell = assoc == ScalarAssociation::Cell || assoc == ScalarAssociation::CellToPoint ||
                        (assoc == ScalarAssociation::Auto && any.shape(0) == nt && nt != n);
      if (assoc == ScalarAssociation::Point && any.shape(0) != n)
        bad(where, "'scalar' has " + std::to_string(any.shape(0)) + " values, and association 'point' needs one per "
                   "point (" + std::to_string(n) + ")");
      if (any.shape(0) != (cell ? nt : n))
        bad(where, "'scalar' has " + std::to_string(any.shape(0)) + " values: one per point (" + std::to_string(n) +
                       ") or one per tet (" + std::to_string(nt) + ")" +
                       (cell && assoc != ScalarAssociation::Auto ? ", and the association needs one per tet" : ""));
      (cell ? m.cell_scalars : m.scalars).assign(any.data(), any.data() + any.size());
    }
    m.points = points_of(pts);
    m.scalar_name = "scalar";
    m.tets.resize(size_t(nt));
    const int64_t* q = t.data();
    for (size_t i = 0; i < m.tets.size(); ++i)
      m.tets[i] = {uint32_t(q[4 * i]), uint32_t(q[4 * i + 1]), uint32_t(q[4 * i + 2]), uint32_t(q[4 * i + 3])};
    if (m.tets.empty()) bad(where, "'tets' is empty");
    if (m.has_cell_scalars() && assoc == ScalarAssociation::CellToPoint) average_cell_scalars_onto_points(m);
    return m;
  }
  std::vector<double> scalars;
  if (!get(d, "scalar", where, false).is_none()) {
    const Array<double> s = floats(d["scalar"], where, "scalar", 0, n);
    scalars.assign(s.data(), s.data() + s.size());
  }
  // VTK's cell arrays: offsets (cells + 1), connectivity, types (cells).
  const Array<int64_t> types = indices(get(d, "types", where, true), where, "types", 0, 256);
  const int64_t cells = types.shape(0);
  const Array<int64_t> conn = indices(get(d, "connectivity", where, true), where, "connectivity", 0, n);
  const Array<int64_t> off =
      indices(get(d, "offsets", where, true), where, "offsets", 0, int64_t(conn.size()) + 1);
  if (off.shape(0) != cells + 1) bad(where, "'offsets' must have one more entry than 'types'");
  for (int64_t c = 0; c < cells; ++c)
    if (off.data()[c] > off.data()[c + 1]) bad(where, "'offsets' must not decrease");
  if (cells > 0 && (off.data()[0] != 0 || off.data()[cells] != int64_t(conn.size())))
    bad(where, "'offsets' must start at 0 and end at the connectivity's length");
  VtkCells vc;
  vc.points = pts.data();
  vc.num_points = n;
  vc.offsets = off.data();
  vc.connectivity = conn.data();
  vc.num_connectivity = int64_t(conn.size());
  vc.types = types.data();
  vc.num_cells = cells;
  vc.scalars = scalars.empty() ? nullptr : scalars.data();
  std::vector<double> cell_scalars;
  if (!get(d, "cell_scalar", where, false).is_none()) {
    const Array<double> s = floats(d["cell_scalar"], where, "cell_scalar", 0, cells);
    cell_scalars.assign(s.data(), s.data() + s.size());
    vc.cell_scalars = cell_scalars.data();
    vc.cell_scalars_float = pybind11::isinstance<pybind11::array_t<float>>(d["cell_scalar"]);
  }
  vc.association = assoc;
  try {
    return tet_mesh_from_cells(vc, where);
  } catch (const std::exception& e) {
    throw pybind11::value_error(e.what());
  }
}

SphereSet sphere_set_from(const pybind11::dict& d, const std::string& where) {
  const char* ckey = d.contains("centres") ? "centres" : "centers";
  const Array<double> c = floats(get(d, ckey, where, true), where, ckey, 3);
  const int64_t n = c.shape(0);
  if (n == 0) bad(where, std::string("'") + ckey + "' is empty");
  const Array<double> r = floats(get(d, "radii", where, true), where, "radii", 0, n);
  SphereSet s;
  s.centres = points_of(c);
  s.radii.assign(r.data(), r.data() + n);
  for (int64_t i = 0; i < n; ++i)
    if (!(s.radii[size_t(i)] > 0)) bad(where, "'radii' must be positive (index " + std::to_string(i) + ")");
  if (d.contains("colors") || d.contains("colours")) {
    const char* key = d.contains("colors") ? "colors" : "colours";
    Array<double> col;
    try {
      col = Array<double>::ensure(d[key]);
    } catch (...) {
    }
    if (!col || col.ndim() != 2 || (col.shape(1) != 3 && col.shape(1) != 4) || col.shape(0) != n)
      bad(where, std::string("'") + key + "' must have shape (" + std::to_string(n) + ", 3) or (" + std::to_string(n) +
                     ", 4)");
    const int64_t k = col.shape(1);
    const double* p = col.data();
    s.rgba.resize(size_t(n));
    for (int64_t i = 0; i < n * k; ++i)
      if (!(p[i] >= 0 && p[i] <= 1)) bad(where, std::string("'") + key + "' values must lie in [0, 1]");
    for (int64_t i = 0; i < n; ++i)
      s.rgba[size_t(i)] = glm::vec4(float(p[k * i]), float(p[k * i + 1]), float(p[k * i + 2]),
                                    k == 4 ? float(p[k * i + 3]) : 1.f);
  }
  if (d.contains("scalar")) {
    const Array<double> v = floats(d["scalar"], where, "scalar", 0, n);
    s.scalars.assign(v.data(), v.data() + n);
    s.scalar_name = "scalar";
  }
  return s;
}

TriangleMesh triangle_mesh_from(const pybind11::dict& d, const std::string& where) {
  const Array<double> pts = floats(get(d, "points", where, true), where, "points", 3);
  const int64_t n = pts.shape(0);
  if (n >= int64_t(UINT32_MAX)) bad(where, "too many points for 32-bit indices");
  const Array<int64_t> t = indices(get(d, "triangles", where, true), where, "triangles", 3, n);
  if (t.shape(0) == 0) bad(where, "'triangles' is empty");
  TriangleMesh m;
  m.points = points_of(pts);
  m.tris.resize(size_t(t.shape(0)));
  const int64_t* q = t.data();
  for (size_t i = 0; i < m.tris.size(); ++i) m.tris[i] = {uint32_t(q[3 * i]), uint32_t(q[3 * i + 1]), uint32_t(q[3 * i + 2])};
  return m;
}

SceneData scene_data_from(const pybind11::dict& data) {
  SceneData out;
  auto each = [&](const char* kind, auto&& add) {
    if (!data.contains(kind)) return;
    for (auto kv : data[kind].cast<pybind11::dict>()) {
      const std::string key = pybind11::str(kv.first);
      if (!pybind11::isinstance<pybind11::dict>(kv.second)) bad(kind, "data must be a dict of arrays");
      add(key, kv.second.cast<pybind11::dict>());
    }
  };
  each("mesh", [&](const std::string& k, const pybind11::dict& d) { out.meshes[k] = tet_mesh_from(d, "mesh"); });
  each("spheres",
       [&](const std::string& k, const pybind11::dict& d) { out.spheres[k] = sphere_set_from(d, "spheres"); });
  each("surfaces", [&](const std::string& k, const pybind11::dict& d) {
    out.surfaces[k] = triangle_mesh_from(d, "surfaces[" + k.substr(k.rfind('/') + 1) + "]");
  });
  return out;
}

}  // namespace zs::python
