// Triangle surfaces (the surface renderer's data, and the casters of the
// shadow-map module): world-space points, triangles as three point ids with
// counter-clockwise winding seen from their front, and the surface each
// triangle belongs to (its colour). A scene's surfaces and ground plane are
// flattened into one mesh, so point ids are global and edges shared by two
// triangles are the same pair of ids (the raster core's watertight tie rule,
// raster/screen_triangle.h, needs that).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/tets/tet_mesh.h"  // Bounds

namespace zs {

struct TriangleMesh {
  std::vector<glm::dvec3> points;
  std::vector<std::array<uint32_t, 3>> tris;
  std::vector<uint32_t> surface;     // per triangle; index into the scene's surfaces (ground: last)
  std::vector<glm::dvec3> normals;   // per point: area-weighted, unit (zero where undefined)
  // Per triangle, closed_solid_sides (geometry/triangles/closed_solids.h); empty when
  // not worked out (nothing is then assumed closed).
  std::vector<int8_t> solid;
  // Per triangle: 1 where both sides can be seen (an open or inconsistently
  // wound surface, not a closed solid), so back-face culling keeps it and it
  // is shaded from the side seen; empty: every triangle one-sided.
  std::vector<uint8_t> two_sided;

  size_t num_points() const { return points.size(); }
  size_t num_tris() const { return tris.size(); }
};

// Appends `b` to `a` (ids shifted), its triangles tagged `surface_id`.
void append_mesh(TriangleMesh& a, const TriangleMesh& b, uint32_t surface_id);

// Fills `normals`: per point, the sum of its triangles' unnormalized face
// normals (so weighted by area), normalized.
void compute_point_normals(TriangleMesh& m);

// The box of every finite point used by a triangle.
Bounds triangle_bounds(const TriangleMesh& m);

// Triangles with zero area or a non-finite point (rendered as nothing).
size_t count_degenerate_tris(const TriangleMesh& m);

// The face normal (unnormalized: twice the area) of triangle t.
glm::dvec3 face_normal(const TriangleMesh& m, size_t t);

}  // namespace zs
