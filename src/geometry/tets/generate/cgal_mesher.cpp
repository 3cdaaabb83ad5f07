// The only translation unit that instantiates CGAL Mesh_3.
#include "geometry/tets/generate/cgal_mesher.h"

#include <cmath>
#include <cstdio>
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

#include "geometry/tets/generate/iso_region.h"
#include "geometry/tets/generate/tet_ops.h"
#include "geometry/tets/generate/voxel_image.h"
#include "geometry/tets/io/stdio_capture.h"
#include "base/util/file_error.h"

namespace zs {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

// Exudation pumps every tet whose smallest dihedral angle is below this
// (degrees). Unbounded (0) it runs 5x longer for the same smallest angle.
constexpr double kExudeBound = 25;

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

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
  if (c.max_points < 4) throw std::invalid_argument("the point limit must be at least 4");
}

// Mesh_3 puts about 0.75 V / s^3 points in a solid of volume V at cell size
// s (0.76-0.82 on the unit sphere, 0.8-1.0 on the skull image); refuse when
// even half of that is over the limit, rather than run for hours.
void check_work(double volume, const Mesh3Criteria& c) {
  const double need = 0.5 * volume / (c.cell_size * c.cell_size * c.cell_size);
  if (need > static_cast<double>(c.max_points))
    throw std::invalid_argument("cell size " + num(c.cell_size) + " needs about " + num(need) +
                                " points for this solid (volume " + num(volume) + "), over the limit of " +
                                std::to_string(c.max_points) + " (--max-points); use a larger size");
}

Criteria make_criteria(const Mesh3Criteria& c) {
  namespace p = CGAL::parameters;
  return Criteria(p::facet_angle = c.facet_angle, p::facet_size = c.facet_size,
                  p::facet_distance = c.facet_distance,
                  p::cell_radius_edge_ratio = c.cell_radius_edge, p::cell_size = c.cell_size);
}

// A labeled domain whose initial surface points are cut from given grid
// edges that cross the surface, instead of Mesh_3's random rays (which never
// stop on an empty domain and rarely hit a small one). Mesh_3 is a template
// on the domain type, so hiding the base's functor is enough.
class SeededDomain : public Domain {
 public:
  SeededDomain(Domain d, const std::vector<std::array<glm::dvec3, 2>>& seeds, unsigned offset)
      : Domain(std::move(d)), seeds_(&seeds), offset_(offset) {}

  struct Construct_initial_points {
    const SeededDomain& d;
    template <class Out>
    Out operator()(Out pts, const int n = 12) const {
      const auto& s = *d.seeds_;
      const size_t want = std::min(static_cast<size_t>(std::max(n, 1)), s.size());
      auto cut = d.construct_intersection_object();
      for (size_t m = 0; m < want; ++m) {
        const auto& e = s[(m * s.size() / want + d.offset_) % s.size()];
        auto x = cut(K::Segment_3(K::Point_3(e[0].x, e[0].y, e[0].z), K::Point_3(e[1].x, e[1].y, e[1].z)));
        if (std::get<2>(x) != 0) *pts++ = std::make_pair(std::get<0>(x), std::get<1>(x));
      }
      return pts;
    }
  };
  Construct_initial_points construct_initial_points_object() const { return {*this}; }

 private:
  const std::vector<std::array<glm::dvec3, 2>>* seeds_;
  unsigned offset_;
};

void ignore_warning(const char*, const char*, const char*, int, const char*) {}

// Restores CGAL's warning handler on every way out.
struct QuietWarnings {
  CGAL::Failure_function old = CGAL::set_warning_handler(ignore_warning);
  ~QuietWarnings() { CGAL::set_warning_handler(old); }
};

// Refinement, then sliver perturbation and exudation as make_mesh_3 would
// run them, but to their bounds rather than to a time limit (its default is
// the refinement's wall-clock time, which made every run differ), and only
// once refinement is known to have stayed under the point limit.
// An unlucky start can leave the complex empty on thin solids: retry with
// the next seeds (make_domain(attempt) varies its start too).
template <class MakeDomain>
C3t3 run(MakeDomain make_domain, const Mesh3Criteria& c) {
  namespace p = CGAL::parameters;
  QuietWarnings quiet;  // CGAL reports the empty start as a warning; we retry
  C3t3 c3t3;
  for (unsigned attempt = 0; attempt < 8; ++attempt) {
    CGAL::get_default_random() = CGAL::Random(static_cast<unsigned>(c.seed) + attempt);
    auto domain = make_domain(attempt);
    CGAL::Mesh_error_code err = CGAL::CGAL_MESH_3_NO_ERROR;
    c3t3 = CGAL::make_mesh_3<C3t3>(
        domain, make_criteria(c), p::no_perturb(), p::no_exude(),
        p::mesh_3_options(p::maximal_number_of_vertices = c.max_points, p::pointer_to_error_code = &err));
    if (err == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED)
      throw std::runtime_error("Mesh_3 reached the limit of " + std::to_string(c.max_points) +
                               " points (--max-points) before meeting the size criteria; use larger sizes");
    if (c3t3.number_of_cells_in_complex() == 0) continue;
    CGAL::perturb_mesh_3(c3t3, domain, p::time_limit = 0);
    CGAL::exude_mesh_3(c3t3, p::sliver_bound = kExudeBound, p::time_limit = 0);
    break;
  }
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

// Volume where f < 0, sampled on a 32^3 grid over the bounding cube.
double implicit_volume(const ImplicitShape& shape) {
  const int n = 32;
  const double r = shape.bounding_radius, h = 2 * r / n;
  size_t in = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) in += shape.f(glm::dvec3(i + 0.5, j + 0.5, k + 0.5) * h - r) < 0;
  return static_cast<double>(in) * h * h * h;
}

}  // namespace

TetMesh mesh_implicit(const ImplicitShape& shape, const Mesh3Criteria& crit) {
  check(crit);
  check_work(implicit_volume(shape), crit);
  auto f = [&shape](const K::Point_3& p) { return shape.f({p.x(), p.y(), p.z()}); };
  const double r = shape.bounding_radius;
  auto make_domain = [&](unsigned) {
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
  // A dozen seeds are all Mesh_3 asks for; 64 leave room for the retries.
  IsoRegion region;
  try {
    region = find_iso_region(voxel_image_from(image, path), iso, inside_above, 64);
    check_work(region.volume, crit);
  } catch (const std::invalid_argument& e) {
    throw FileError(path, e.what());
  }
  // Label 1 on the requested side of the iso-value; outside the image counts
  // as the other side so the solid is closed at the image border.
  const double outside = inside_above ? iso - 1.0 - std::abs(iso) : iso + 1.0 + std::abs(iso);
  auto to_label = [iso, inside_above](double v) { return (inside_above ? v > iso : v < iso) ? 1 : 0; };
  auto make_domain = [&](unsigned attempt) {
    return SeededDomain(Domain::create_gray_image_mesh_domain(
                            image, CGAL::parameters::iso_value = iso, CGAL::parameters::value_outside = outside,
                            CGAL::parameters::image_values_to_subdomain_indices = to_label),
                        region.crossings, attempt * 5);
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
