// The tetrahedral mesh every renderer starts from: positions, one scalar per
// vertex (point data) or one per tet (cell data), and four vertex indices per
// tet. Topology lives in topology.h and is built once from this.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace zs {

using Tet = std::array<uint32_t, 4>;

struct TetMesh {
  std::vector<glm::dvec3> points;
  std::vector<double> scalars;       // one per point (empty = no point scalar)
  std::vector<double> cell_scalars;  // one per tet: cell-centred data, constant in the tet (empty = none)
  std::vector<Tet> tets;

  std::string scalar_name;      // e.g. "density"; empty when unnamed
  // Why a reader chose this scalar when none was named and its default was
  // constant, e.g. "'Density' is constant (1)"; empty otherwise.
  std::string scalar_choice;
  // Things a reader did to the data that a user should know (cell->point
  // averaging, hex splitting, merged points...). Printed by `mesh info`.
  std::vector<std::string> notes;

  size_t num_points() const { return points.size(); }
  size_t num_tets() const { return tets.size(); }
  // Point scalars; a mesh has at most one of point and cell scalars.
  bool has_scalars() const { return !scalars.empty(); }
  bool has_cell_scalars() const { return !cell_scalars.empty(); }
  // The scalar's values whichever their association (ranges, defaults).
  const std::vector<double>& scalar_values() const { return cell_scalars.empty() ? scalars : cell_scalars; }
};

// Cell data -> point data: each point gets the mean of the values of the
// tets that use it (points no tet uses: 0); notes it in m.notes.
void average_cell_scalars_onto_points(TetMesh& m);

// Six times the signed volume of tet t: (b-a) . ((c-a) x (d-a)).
double signed_volume6(const TetMesh& m, const Tet& t);

// Axis-aligned bounds of the points (ignores non-finite coordinates).
struct Bounds {
  glm::dvec3 lo{0.0}, hi{0.0};
  bool empty = true;
  // Half the diagonal, and the centre: computed so that coordinates near the
  // largest double do not overflow (the full diagonal may still be inf).
  double half_diagonal() const;
  double diagonal() const { return 2.0 * half_diagonal(); }
  glm::dvec3 centre() const { return empty ? glm::dvec3(0.0) : 0.5 * lo + 0.5 * hi; }
};
Bounds bounds_of(const TetMesh& m);

}  // namespace zs
