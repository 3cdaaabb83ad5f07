// The only translation unit that instantiates CGAL Mesh_3.
#include "mesh/generate/cgal_mesher.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Image_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#include "mesh/generate/tet_ops.h"
#include "mesh/io/stdio_capture.h"
#include "util/file_error.h"

namespace zs {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

void check(const Mesh3Criteria& c) {
  auto pos = [](double v, const char* what) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be positive");
  };
  pos(c.facet_size, "facet size");
  pos(c.facet_distance, "facet distance");
  pos(c.cell_size, "cell size");
  if (!(c.facet_angle > 0 && c.facet_angle <= 30))
    throw std::invalid_argument("facet angle must be in (0, 30] degrees (Mesh_3 may not terminate above 30)");
  if (!(c.cell_radius_edge >= 2))
    throw std::invalid_argument("cell radius-edge ratio must be >= 2 for Mesh_3 to terminate");
}

Criteria make_criteria(const Mesh3Criteria& c) {
  namespace p = CGAL::parameters;
  return Criteria(p::facet_angle = c.facet_angle, p::facet_size = c.facet_size,
                  p::facet_distance = c.facet_distance,
                  p::cell_radius_edge_ratio = c.cell_radius_edge, p::cell_size = c.cell_size);
}

// Mesh_3 (perturbation, exudation) and the domain's surface oracle draw from
// CGAL's default generator, seeded in run(). Output can still differ by a few
// tets between runs (Mesh_3 breaks some ties by handle address).
void ignore_warning(const char*, const char*, const char*, int, const char*) {}

// make_mesh_3 seeds its surface from random rays through the domain; on thin
// solids (an image's skull) an unlucky draw finds no surface and the mesh is
// empty. Retry with the next seeds before giving up.
template <class MakeDomain>
C3t3 run(MakeDomain make_domain, const Mesh3Criteria& c) {
  // CGAL reports the empty start as a warning on stderr; we retry instead.
  auto old = CGAL::set_warning_handler(ignore_warning);
  C3t3 c3t3;
  for (unsigned attempt = 0; attempt < 8; ++attempt) {
    CGAL::get_default_random() = CGAL::Random(static_cast<unsigned>(c.seed) + attempt);
    Domain domain = make_domain();
    c3t3 = CGAL::make_mesh_3<C3t3>(domain, make_criteria(c));
    if (c3t3.number_of_cells_in_complex() > 0) break;
  }
  CGAL::set_warning_handler(old);
  return c3t3;
}

// Tets of the complex (cells_in_complex), vertices compacted in first-use order.
TetMesh extract(const C3t3& c3t3) {
  const Tr& tr = c3t3.triangulation();
  auto bare = tr.geom_traits().construct_point_3_object();
  std::unordered_map<Tr::Vertex_handle, uint32_t> index;
  TetMesh m;
  m.tets.reserve(c3t3.number_of_cells_in_complex());
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    Tet t;
    for (int k = 0; k < 4; ++k) {
      Tr::Vertex_handle v = c->vertex(k);
      auto [it, fresh] = index.try_emplace(v, static_cast<uint32_t>(m.points.size()));
      if (fresh) {
        const auto p = bare(tr.point(v));
        m.points.push_back({p.x(), p.y(), p.z()});
      }
      t[k] = it->second;
    }
    m.tets.push_back(t);
  }
  if (m.tets.empty()) throw std::runtime_error("Mesh_3 produced no tetrahedra (domain empty or criteria too coarse)");
  finalize_generated(m);
  return m;
}

}  // namespace

TetMesh mesh_implicit(const ImplicitShape& shape, const Mesh3Criteria& crit) {
  check(crit);
  auto f = [&shape](const K::Point_3& p) { return shape.f({p.x(), p.y(), p.z()}); };
  const double r = shape.bounding_radius;
  auto make_domain = [&] {
    // Sphere_3 takes the squared radius.
    return Domain::create_implicit_mesh_domain(
        f, K::Sphere_3(CGAL::ORIGIN, r * r), CGAL::parameters::relative_error_bound = 1e-6,
        CGAL::parameters::p_rng = &CGAL::get_default_random());
  };
  return extract(run(make_domain, crit));
}

TetMesh mesh_gray_image(const std::string& path, double iso, bool inside_above,
                        const Mesh3Criteria& crit) {
  check(crit);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
  CGAL::Image_3 image;
  bool ok;
  {
    StdioCapture quiet(2);  // ImageIO explains failures on stderr; we say one line
    ok = image.read(path);
  }
  if (!ok) throw FileError(path, "cannot read 3D image (expected .inr/.inr.gz, ...)");
  // Label 1 on the requested side of the iso-value; outside the image counts
  // as the other side so the solid is closed at the image border.
  const double outside = inside_above ? iso - 1.0 - std::abs(iso) : iso + 1.0 + std::abs(iso);
  auto to_label = [iso, inside_above](double v) { return (inside_above ? v > iso : v < iso) ? 1 : 0; };
  auto make_domain = [&] {
    return Domain::create_gray_image_mesh_domain(
        image, CGAL::parameters::iso_value = iso, CGAL::parameters::value_outside = outside,
        CGAL::parameters::image_values_to_subdomain_indices = to_label,
        CGAL::parameters::p_rng = &CGAL::get_default_random());
  };
  try {
    TetMesh m = extract(run(make_domain, crit));
    m.notes.push_back("generated from " + path + " (iso " + std::to_string(iso) + ")");
    return m;
  } catch (const std::runtime_error& e) {
    throw FileError(path, e.what());
  }
}

}  // namespace zs
