// zsweep.generate: the mesh and sphere-set generators of `zsweep mesh
// generate` and `zsweep spheres generate`, returning arrays instead of files.
#include "python/py_generate.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "geometry/tets/generate/cgal_mesher.h"
#include "geometry/tets/generate/grid_mesh.h"
#include "geometry/tets/generate/implicit_shapes.h"
#include "geometry/tets/generate/scalar_fields.h"
#include "geometry/tets/generate/shape_mesher.h"
#include "geometry/tets/generate/shapes.h"
#include "geometry/tets/generate/surface_io.h"
#include "geometry/tets/generate/tetgen_mesher.h"
#include "geometry/tets/generate/voxel_image.h"
#include "geometry/spheres/generate/demo_image.h"
#include "geometry/spheres/generate/pore_balls.h"
#include "geometry/spheres/generate/test_sets.h"

namespace py = pybind11;

namespace zs::python {

namespace {

void check_field(const std::string& field) {
  const std::vector<std::string>& names = field_names();
  if (field != "none" && std::find(names.begin(), names.end(), field) == names.end()) {
    std::string all;
    for (const std::string& n : names) all += n + ", ";
    throw py::value_error("field must be one of " + all + "none, not '" + field + "'");
  }
}

// Everything heavy runs with the GIL released.
template <class F>
TetMesh without_gil(F&& f) {
  py::gil_scoped_release nogil;
  return f();
}

py::dict mesh_dict(const TetMesh& m) {
  py::array_t<double> p({m.num_points(), size_t(3)});
  py::array_t<int64_t> t({m.num_tets(), size_t(4)});
  double* pp = p.mutable_data();
  for (size_t i = 0; i < m.num_points(); ++i)
    for (int k = 0; k < 3; ++k) pp[3 * i + k] = m.points[i][k];
  int64_t* tp = t.mutable_data();
  for (size_t i = 0; i < m.num_tets(); ++i)
    for (int k = 0; k < 4; ++k) tp[4 * i + k] = m.tets[i][k];
  py::dict d;
  d["points"] = p;
  d["tets"] = t;
  if (m.has_scalars()) d["scalar"] = py::array_t<double>(m.scalars.size(), m.scalars.data());
  return d;
}

// The same criteria as the CLI's for the same arguments, so both give the
// same mesh (Mesh_3 is deterministic for given criteria and seed).
Mesh3Criteria criteria(std::optional<double> size, double default_size, uint64_t seed, size_t max_points) {
  if (size && !(*size > 0 && std::isfinite(*size))) throw py::value_error("size must be a positive number");
  if (max_points < 4) throw py::value_error("max_points must be at least 4");
  Mesh3Criteria c = Mesh3Criteria::from_size(size.value_or(default_size));
  c.seed = seed;
  c.max_points = max_points;
  return c;
}

py::dict shape(const std::string& name, size_t tets, double quality, const std::string& field, uint64_t seed) {
  if (!find_shape(name)) {
    std::string all;
    for (const ShapeInfo& s : shape_catalog()) all += (all.empty() ? "" : ", ") + s.name;
    throw py::value_error("unknown shape '" + name + "' (shapes: " + all + ")");
  }
  if (tets < 1 || tets > 100000000) throw py::value_error("tets must be in [1, 100000000]");
  if (!(quality >= 1.1 && quality <= 100)) throw py::value_error("quality must be in [1.1, 100]");
  check_field(field);
  return mesh_dict(without_gil([&] {
    ShapeMeshOptions o;
    o.shape = name;
    o.target_tets = tets;
    o.quality = quality;
    o.seed = seed;
    TetMesh m = mesh_shape(o);
    if (field != "none") apply_field(m, field, seed);
    return m;
  }));
}

py::dict surface(const std::string& path, double quality, double max_volume, bool preserve_surface,
                 const std::string& field, uint64_t seed, size_t max_tets) {
  if (!(quality == 0 || (quality >= 1.1 && quality <= 100))) throw py::value_error("quality must be 0 or in [1.1, 100]");
  if (!(max_volume >= 0) || !std::isfinite(max_volume))
    throw py::value_error("max_volume must be 0 (none) or a positive number");
  if (max_tets < 4) throw py::value_error("max_tets must be at least 4");
  check_field(field);
  return mesh_dict(without_gil([&] {
    TetgenOptions o;
    o.quality = quality;
    o.max_volume = max_volume;
    o.preserve_surface = preserve_surface;
    o.max_tets = max_tets;
    const Plc plc = read_surface(path);
    TetMesh m;
    try {
      m = tetrahedralize(plc, o);
    } catch (const std::exception& e) {  // TetGen's failures and the work bound alike
      throw std::runtime_error(path + ": " + e.what());
    }
    if (field != "none") apply_field(m, field, seed);
    return m;
  }));
}

py::dict implicit(const std::string& name, std::optional<double> size, const std::string& field, uint64_t seed,
                  size_t max_points) {
  const ImplicitShape* s = find_implicit(name);
  if (!s) {
    std::string all;
    for (const ImplicitShape& i : implicit_catalog()) all += (all.empty() ? "" : ", ") + i.name;
    throw py::value_error("unknown implicit solid '" + name + "' (solids: " + all + ")");
  }
  check_field(field);
  return mesh_dict(without_gil([&] {
    TetMesh m = mesh_implicit(*s, criteria(size, 0.1, seed, max_points));
    if (field != "none") apply_field(m, field, seed);
    return m;
  }));
}

py::dict image(const std::string& path, double iso, bool below, std::optional<double> size, const std::string& field,
               uint64_t seed, size_t max_points) {
  check_field(field);
  criteria(size, 1, seed, max_points);  // checks the arguments before reading the image
  return mesh_dict(without_gil([&] {
    const VoxelImage img = read_voxel_image(path);
    const double voxel = std::max({img.spacing.x, img.spacing.y, img.spacing.z});
    TetMesh m = mesh_gray_image(path, iso, !below, criteria(size, 2 * voxel, seed, max_points));
    if (field != "none") apply_field(m, field, seed, &img);
    return m;
  }));
}

// cells: (NX, NY, NZ), from an int or a sequence in generate.py. The
// generator's own checks (split, jitter, ids, memory) raise ValueError.
py::dict grid(const std::vector<int64_t>& cells, int split, double jitter, const std::string& field, uint64_t seed) {
  if (cells.size() != 3) throw py::value_error("cells must be N or (NX, NY, NZ)");
  GridMeshOptions o;
  for (int a = 0; a < 3; ++a) {
    if (cells[a] < 1 || cells[a] > int64_t(UINT32_MAX) - 1)
      throw py::value_error("cells must be in [1, " + std::to_string(UINT32_MAX - 1) + "], not " +
                            std::to_string(cells[a]));
    o.cells[a] = uint32_t(cells[a]);
  }
  o.split = split;
  o.jitter = jitter;
  o.seed = seed;
  check_field(field);
  return mesh_dict(without_gil([&] {
    TetMesh m = make_grid_mesh(o);
    if (field != "none") apply_field(m, field, seed);
    return m;
  }));
}

py::dict spheres(const std::string& set, size_t count, uint64_t seed) {
  SphereTestSet t;
  if (!parse_sphere_test_set(set, &t))
    throw py::value_error("unknown sphere test set '" + set + "' (expected c1, c2, c3 or c4)");
  SphereSet s;
  {
    py::gil_scoped_release nogil;
    const size_t n = count ? count : default_sphere_count(t);
    switch (t) {
      case SphereTestSet::C1: s = generate_c1(n, seed); break;
      case SphereTestSet::C2: s = generate_c2(n, seed, kCgalDemoData); break;
      case SphereTestSet::C3: s = generate_c3(n, seed); break;
      case SphereTestSet::C4: s = generate_c4(n, seed); break;
    }
  }
  const size_t n = s.size();
  py::array_t<double> c({n, size_t(3)});
  double* cp = c.mutable_data();
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) cp[3 * i + k] = s.centres[i][k];
  py::dict d;
  d["centers"] = c;
  d["radii"] = py::array_t<double>(n, s.radii.data());
  if (s.has_rgba()) {
    py::array_t<double> col({n, size_t(4)});
    double* q = col.mutable_data();
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 4; ++k) q[4 * i + k] = s.rgba[i][k];
    d["colors"] = col;
  }
  return d;
}

}  // namespace

void add_generate(py::module_& m) {
  m.def("generate_shape", &shape, py::arg("name"), py::arg("tets") = 10000, py::arg("quality") = 1.414,
        py::arg("field") = "radial", py::arg("seed") = 1);
  m.def("generate_surface", &surface, py::arg("path"), py::arg("quality") = 1.414, py::arg("max_volume") = 0.0,
        py::arg("preserve_surface") = false, py::arg("field") = "distance", py::arg("seed") = 1,
        py::arg("max_tets") = TetgenOptions().max_tets);
  m.def("generate_implicit", &implicit, py::arg("name"), py::arg("size") = py::none(), py::arg("field") = "distance",
        py::arg("seed") = 1, py::arg("max_points") = Mesh3Criteria().max_points);
  m.def("generate_image", &image, py::arg("path"), py::arg("iso"), py::arg("below") = false,
        py::arg("size") = py::none(), py::arg("field") = "image", py::arg("seed") = 1,
        py::arg("max_points") = Mesh3Criteria().max_points);
  m.def("generate_grid", &grid, py::arg("cells"), py::arg("split") = 5, py::arg("jitter") = 0.0,
        py::arg("field") = "gaussians", py::arg("seed") = 1);
  m.def("generate_spheres", &spheres, py::arg("set"), py::arg("count") = 0, py::arg("seed") = 1);
  m.def("shapes", [] {
    std::vector<std::string> v;
    for (const ShapeInfo& s : shape_catalog()) v.push_back(s.name);
    return v;
  });
  m.def("implicit_solids", [] {
    std::vector<std::string> v;
    for (const ImplicitShape& s : implicit_catalog()) v.push_back(s.name);
    return v;
  });
  m.def("fields", [] { return field_names(); });
}

}  // namespace zs::python
