// Mesh validation: every anomaly is counted, nothing throws. Readers accept a
// mesh with anomalies; the renderer decides what to skip and counts it.
#pragma once

#include <cstddef>
#include <string>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"

namespace zs {

struct ValidationReport {
  size_t positive_tets = 0;        // signed volume > 0 (one winding)
  size_t negative_tets = 0;        // signed volume < 0 (the other winding)
  size_t zero_volume_tets = 0;     // |6V| <= eps * (longest edge)^3
  size_t repeated_index_tets = 0;  // a tet naming one vertex twice (also zero-volume)
  size_t nonfinite_tets = 0;       // a corner with NaN/Inf coordinates
  size_t duplicate_points = 0;     // points coinciding with an earlier point
  size_t unused_points = 0;        // referenced by no tet
  size_t nonfinite_points = 0;     // NaN/Inf coordinate
  size_t nonfinite_scalars = 0;    // NaN/Inf scalar
  size_t nonmanifold_faces = 0;    // faces shared by more than two tets
  size_t coincident_boundary_faces = 0;  // boundary faces lying on another boundary face
  double volume = 0.0;             // sum of |V| over finite tets
  double zero_volume_eps = 0.0;    // the relative epsilon used

  // "Inverted" only has a meaning relative to a majority orientation: mixed
  // winding is normal in tet files (spx: 12 vs 12,924), so the minority count
  // is reported, not treated as an error.
  size_t minority_orientation() const {
    return positive_tets < negative_tets ? positive_tets : negative_tets;
  }
  bool clean() const;
};

// Tets with a non-finite coordinate or scalar at a vertex: the renderers
// leave them empty (they are counted, not rendered), and the CLI warns.
size_t count_nonfinite_tets(const TetMesh& m);

ValidationReport validate(const TetMesh& m, const Topology& topo,
                          double zero_volume_eps = 1e-10);

}  // namespace zs
