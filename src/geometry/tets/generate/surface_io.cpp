#include "geometry/tets/generate/surface_io.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "geometry/tets/generate/surface_precheck.h"
#include "base/util/file_error.h"

namespace zs {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// TetGen 1.5's library crashes (double free) instead of reporting a
// self-intersecting PLC, so check with CGAL first.
static bool self_intersects(const Plc& plc) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<K::Point_3> pts;
  for (const glm::dvec3& p : plc.points) pts.emplace_back(p.x, p.y, p.z);
  std::vector<std::array<std::size_t, 3>> tris;
  for (const auto& t : plc.triangles()) tris.push_back({t[0], t[1], t[2]});
  PMP::orient_polygon_soup(pts, tris);  // may duplicate points at non-manifold vertices
  CGAL::Surface_mesh<K::Point_3> sm;
  PMP::polygon_soup_to_polygon_mesh(pts, tris, sm);
  return PMP::does_self_intersect(sm);
}

Plc read_surface(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
  // CGAL's readers allocate by counts in the file, and its PLY reader trusts
  // the header's types: check both first (surface_precheck.h).
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".off") precheck_off(path);
  if (ext == ".stl") precheck_stl(path);
  if (ext == ".ply") precheck_ply(path);
  std::vector<K::Point_3> pts;
  std::vector<std::vector<std::size_t>> polys;
  bool ok = false;
  {
    // CGAL's readers explain failures on std::cerr; we report one line instead.
    std::ostringstream sink;
    std::streambuf* old = std::cerr.rdbuf(sink.rdbuf());
    try {
      ok = CGAL::IO::read_polygon_soup(path, pts, polys);
    } catch (...) {
      ok = false;
    }
    std::cerr.rdbuf(old);
  }
  if (!ok) throw FileError(path, "cannot read surface (expected a triangle .off, .stl, .ply or .obj)");
  if (polys.empty()) throw FileError(path, "surface has no faces");

  // OFF/PLY soups may repeat a point under two indices; TetGen would see a
  // duplicate vertex, so merge exact duplicates.
  Plc plc;
  std::vector<uint32_t> merged(pts.size());
  {
    std::map<std::array<double, 3>, uint32_t> seen;
    for (size_t i = 0; i < pts.size(); ++i) {
      auto [it, fresh] = seen.try_emplace({pts[i].x(), pts[i].y(), pts[i].z()},
                                          static_cast<uint32_t>(plc.points.size()));
      if (fresh) plc.add_point({pts[i].x(), pts[i].y(), pts[i].z()});
      merged[i] = it->second;
    }
  }
  for (const auto& poly : polys) {
    if (poly.size() < 3) throw FileError(path, "face with fewer than 3 corners");
    for (std::size_t v : poly)
      if (v >= pts.size()) throw FileError(path, "face refers to a missing vertex");
    for (size_t k = 1; k + 1 < poly.size(); ++k)
      plc.add_triangle(merged[poly[0]], merged[poly[k]], merged[poly[k + 1]]);
  }

  // TetGen needs a watertight boundary; say so here rather than let it fail
  // obscurely. Count each undirected edge's uses.
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const PlcFacet& f : plc.facets) {
    const auto& t = f.polygons[0];
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a == b) throw FileError(path, "degenerate face (repeated vertex)");
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  size_t open = 0, nonmanifold = 0;
  for (const auto& [e, n] : uses) {
    if (n == 1) ++open;
    if (n > 2) ++nonmanifold;
  }
  if (open) throw FileError(path, "surface is not closed (" + std::to_string(open) + " boundary edges)");
  if (nonmanifold)
    throw FileError(path, "surface is non-manifold (" + std::to_string(nonmanifold) + " edges on 3+ faces)");
  if (self_intersects(plc)) throw FileError(path, "surface intersects itself (TetGen needs a valid closed surface)");
  return plc;
}

}  // namespace zs
