#include "scene/surface_input.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "geometry/triangles/clip_triangles.h"
#include "geometry/triangles/closed_solids.h"
#include "geometry/triangles/ground_height.h"
#include "geometry/triangles/io/mesh_surfaces.h"
#include "geometry/triangles/io/surface_reader.h"

namespace zs {

namespace {

glm::dvec3 rotate(const glm::dvec3& p, const glm::dvec3& deg) {
  const glm::dvec3 a = deg * (M_PI / 180.0);
  glm::dvec3 q = p;
  // Rx, then Ry, then Rz.
  q = {q.x, std::cos(a.x) * q.y - std::sin(a.x) * q.z, std::sin(a.x) * q.y + std::cos(a.x) * q.z};
  q = {std::cos(a.y) * q.x + std::sin(a.y) * q.z, q.y, -std::sin(a.y) * q.x + std::cos(a.y) * q.z};
  q = {std::cos(a.z) * q.x - std::sin(a.z) * q.y, std::sin(a.z) * q.x + std::cos(a.z) * q.y, q.z};
  return q;
}

}  // namespace

void load_surfaces(SceneInput& in, const std::map<std::string, TriangleMesh>* data) {
  SurfaceScene& ss = in.scene.surfaces;
  TriangleMesh all;
  for (size_t i = 0; i < ss.surfaces.size(); ++i) {
    const SurfaceEntry& e = ss.surfaces[i];
    SurfaceReadCounts rc;
    const std::string mesh_name = in.scene.mesh_path.empty() ? "default mesh" : in.scene.mesh_path;
    TriangleMesh m = e.source == SurfaceSource::Boundary     ? boundary_surface(in.mesh, mesh_name)
                     : e.source == SurfaceSource::Isosurface ? isosurfaces(in.mesh, e.iso_values, mesh_name)
                     : data && data->count(e.path)           ? data->at(e.path)
                                                             : read_surface(e.path, &rc);
    in.surface_polygons_split += rc.split;
    in.surface_elements_dropped += rc.dropped;
    for (glm::dvec3& p : m.points) p = e.translate + rotate(e.scale * p, e.rotate_deg);
    append_mesh(all, m, uint32_t(i));
  }
  // clip_geometry: the volume's planes cut the surfaces too, before anything
  // is worked out of them (a cut solid is open: seen from both sides).
  if (in.scene.clip_geometry) in.surface_clip = clip_triangles(all, in.scene.settings.clip);
  // Inward-wound solids would show their insides; open surfaces are drawn
  // from both sides instead (closed_solids.h).
  in.surface_solids = turn_solids_outward(all);
  std::vector<int8_t> solid = all.solid;
  const size_t n = all.num_tris();
  if (ss.ground) {
    const Bounds b = triangle_bounds(all);
    const glm::dvec3 c = b.centre();
    const double ext = b.empty ? 1.0 : std::max({b.hi.x - b.lo.x, b.hi.z - b.lo.z, 1e-300});
    if (ss.ground_auto_height) {
      const GroundPlacement g = auto_ground_height(all);
      ss.ground_height = g.height;
      in.ground_lowered_by = g.lowered ? g.gap : 0.0;
    }
    const double h = ss.ground_height;
    const double s = 2.0 * ext;  // half side
    TriangleMesh g;
    g.points = {{c.x - s, h, c.z - s}, {c.x + s, h, c.z - s}, {c.x + s, h, c.z + s}, {c.x - s, h, c.z + s}};
    // Counter-clockwise seen from +y.
    g.tris = {{0, 2, 1}, {0, 3, 2}};
    append_mesh(all, g, uint32_t(ss.surfaces.size()));
  }
  compute_point_normals(all);
  // The ground is open but one-sided: a floor, seen from above only.
  solid.resize(all.num_tris(), 0);
  all.solid = std::move(solid);
  all.two_sided.assign(all.num_tris(), 0);
  for (size_t t = 0; t < n; ++t) all.two_sided[t] = all.solid[t] == 0;
  in.surface = std::move(all);
}

Camera frame_surfaces(const Bounds& b, Projection projection, uint32_t width, uint32_t height) {
  Camera cam = frame_bounds(b, projection, width, height);
  const double dist = glm::length(cam.eye - cam.target);
  cam.eye = cam.target + glm::normalize(glm::dvec3(0.6, 0.5, 1.0)) * dist;
  return cam;
}

}  // namespace zs
