#include "cli/surface_info.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "geometry/triangles/closed_solids.h"
#include "geometry/triangles/io/surface_reader.h"

namespace zs {

void print_surface_info(const std::string& path, bool json) {
  SurfaceReadCounts rc;
  const TriangleMesh m = read_surface(path, &rc);  // never empty: the reader refuses that
  SolidCounts sc;
  const std::vector<int8_t> side = closed_solid_sides(m, &sc);
  const size_t two_sided = size_t(std::count(side.begin(), side.end(), int8_t(0)));
  const size_t degenerate = count_degenerate_tris(m);
  const Bounds b = triangle_bounds(m);
  if (json) {
    nlohmann::json j = {
        {"file", path},
        {"kind", "surface"},
        {"points", m.num_points()},
        {"triangles", m.num_tris()},
        {"polygons", rc.polygons},
        {"polygons_split", rc.split},
        {"elements_dropped", rc.dropped},
        {"degenerate_triangles", degenerate},
        {"components", sc.components},
        {"closed_solids", sc.closed},
        {"closed_solids_wound_inward", sc.inward},
        {"two_sided_triangles", two_sided},
        {"bounds", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}},
    };
    std::cout << j.dump(2) << "\n";
    return;
  }
  auto line = [](const char* key, const std::string& v) { std::printf("%-27s %s\n", key, v.c_str()); };
  auto n = [](size_t v) { return std::to_string(v); };
  char buf[256];
  line("file:", path);
  line("kind:", "triangle surface (zsweep render draws it; mesh convert takes tet meshes only)");
  line("points:", n(m.num_points()));
  line("triangles:", n(m.num_tris()));
  line("polygons in file:", n(rc.polygons) + " (" + n(rc.split) + " with more than three corners, split)");
  line("dropped on read:", n(rc.dropped) + " (lines, points, faces of fewer than three corners)");
  line("degenerate triangles:", n(degenerate) + " (zero area: drawn as nothing)");
  line("components:", n(sc.components) + " (joined by edges two triangles share, wound alike)");
  line("closed solids:", n(sc.closed) + " (" + n(sc.inward) + " wound inward: turned outward when rendered)");
  line("two-sided triangles:", n(two_sided) + " (on no closed solid: drawn from both sides)");
  std::snprintf(buf, sizeof buf, "[%.9g, %.9g, %.9g] - [%.9g, %.9g, %.9g]", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y,
                b.hi.z);
  line("bounds:", buf);
}

}  // namespace zs
