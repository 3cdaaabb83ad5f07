// Walking a line through the mesh's face adjacency: from a boundary entry
// face, tet by tet, to the boundary face where the line leaves. In each tet
// the barycentric coordinates are linear along the line,
//   lambda_k(t) = lambda_k(o) + t · (grad lambda_k · d),
// so the exit is the smallest t where a coordinate of a face the line is
// leaving through reaches zero, and the scalar at any t is sum lambda_k s_k
// (cell data: the tet's own value) — no projection, no screen space, nothing
// shared with the sweep.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"

namespace zs {

// The mesh as the reference sees it: flat (zero-volume) tets hold no volume
// and are left out, so a face is interior when it has two solid tets, and
// boundary when it has one. A flat tet between two solid ones becomes a pair
// of coincident boundary faces — a seam the line leaves and re-enters at the
// same t. Non-manifold faces (more than two tets, only ever with flat ones
// among them) are resolved here too.
struct SolidFaces {
  std::vector<uint8_t> flat;                      // per tet
  std::vector<std::array<uint32_t, 2>> tets;      // per face: solid tets, kNoTet padded
  std::vector<std::array<uint32_t, 4>> tet_faces;  // per tet: face k opposite local vertex k (build_tet_faces)
  bool boundary(uint32_t f) const { return tets[f][0] != kNoTet && tets[f][1] == kNoTet; }
};
SolidFaces build_solid_faces(const TetMesh& m, const Topology& topo);
bool tet_is_flat(const TetMesh& m, const Tet& t);

// One piece of the line inside one tet: [t0, t1] with the scalar at each end.
struct WalkSegment {
  double t0, t1, s0, s1;
  uint32_t tet;
};

struct WalkResult {
  double t_exit;       // where the line left the mesh (or the walk gave up)
  uint32_t steps = 0;  // tets visited
  bool lost = false;   // no exit found (rounding in a near-flat tet); the line re-enters at the next boundary face
};

// Walks from boundary face `entry_face` (entered at t_entry) until the line
// leaves through a boundary face, calling emit(WalkSegment) for each tet.
template <class Emit>
WalkResult walk_line(const TetMesh& m, const Topology& topo, const SolidFaces& solid, const glm::dvec3& o,
                     const glm::dvec3& d, uint32_t entry_face, double t_entry, Emit&& emit);

// Per-tet step, exposed for the template above and for tests: the tet's exit
// face (local index) and t, given the face it was entered through. Returns
// false when there is no exit in the line's direction (a flat tet).
bool tet_exit(const TetMesh& m, const SolidFaces& solid, uint32_t tet, uint32_t entered_face, const glm::dvec3& o,
              const glm::dvec3& d, int* exit_local, double* t_exit, double lambda_o[4], double dlambda[4]);

template <class Emit>
WalkResult walk_line(const TetMesh& m, const Topology& topo, const SolidFaces& solid, const glm::dvec3& o,
                     const glm::dvec3& d, uint32_t entry_face, double t_entry, Emit&& emit) {
  WalkResult r{t_entry};
  uint32_t tet = solid.tets[entry_face][0], face = entry_face;
  const uint64_t max_steps = 4 * uint64_t(m.num_tets()) + 16;
  double t = t_entry;
  for (uint64_t step = 0; step < max_steps; ++step) {
    ++r.steps;
    int k;
    double t1, lo[4], dl[4];
    if (!tet_exit(m, solid, tet, face, o, d, &k, &t1, lo, dl)) {
      r.lost = true;
      break;
    }
    t1 = std::max(t1, t);
    const Tet& tv = m.tets[tet];
    double s0 = 0, s1 = 0;
    if (m.has_cell_scalars()) {
      s0 = s1 = m.cell_scalars[tet];  // cell data: constant in the tet
    } else {
      for (int q = 0; q < 4; ++q) {
        s0 += (lo[q] + t * dl[q]) * m.scalars[tv[q]];
        s1 += (lo[q] + t1 * dl[q]) * m.scalars[tv[q]];
      }
    }
    emit(WalkSegment{t, t1, s0, s1, tet});
    t = t1;
    face = solid.tet_faces[tet][size_t(k)];
    const auto& ft = solid.tets[face];
    if (ft[1] == kNoTet) break;  // left the (solid) mesh
    tet = ft[0] == tet ? ft[1] : ft[0];
  }
  r.t_exit = t;
  return r;
}

}  // namespace zs
