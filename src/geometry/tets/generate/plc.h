// A piecewise linear complex: the boundary description TetGen meshes (-p).
// Facets are planar polygons (possibly with holes); a closed triangle surface
// is the special case of one triangle per facet.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

struct PlcFacet {
  std::vector<std::vector<uint32_t>> polygons;  // outer loop first, then hole loops
  std::vector<glm::dvec3> holes;                // one point inside each facet hole
};

struct Plc {
  std::vector<glm::dvec3> points;
  std::vector<PlcFacet> facets;
  std::vector<glm::dvec3> holes;  // a point inside each enclosed cavity

  uint32_t add_point(const glm::dvec3& p) {
    points.push_back(p);
    return static_cast<uint32_t>(points.size() - 1);
  }
  void add_polygon(std::vector<uint32_t> loop) { facets.push_back({{std::move(loop)}, {}}); }
  void add_triangle(uint32_t a, uint32_t b, uint32_t c) { add_polygon({a, b, c}); }

  // True when every facet is a single triangle (what -Y preservation and the
  // surface tests reason about).
  bool is_triangle_surface() const {
    for (const PlcFacet& f : facets)
      if (f.polygons.size() != 1 || f.polygons[0].size() != 3) return false;
    return true;
  }
  std::vector<std::array<uint32_t, 3>> triangles() const {
    std::vector<std::array<uint32_t, 3>> t;
    for (const PlcFacet& f : facets)
      if (f.polygons.size() == 1 && f.polygons[0].size() == 3)
        t.push_back({f.polygons[0][0], f.polygons[0][1], f.polygons[0][2]});
    return t;
  }
};

}  // namespace zs
