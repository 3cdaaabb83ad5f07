// Renumbering a tet mesh for locality (docs/scaling.md): points in the order
// of a Morton curve through their bounding box, tets by their first point in
// that order. Topology, the per-view passes and the sweep then touch memory
// in order; on a mesh whose numbering is scattered (a shuffled 10 M-tet grid)
// that is the difference between seconds and tenths per phase. The mesh is
// the same set of tets over the same points: only the ids change. Images
// stay the same where no two vertices tie in depth; where they do, the
// sweep takes tied vertices (and a face's vertices) in id order, so the
// last bits of a pixel may change (kiefer: 1e-4). Renders therefore never
// renumber on their own: `zsweep mesh convert --renumber` writes a new mesh.
#pragma once

#include <cstdint>

#include "geometry/tets/tet_mesh.h"

namespace zs {

struct RenumberStats {
  double spread_before = 0, spread_after = 0;  // id_spread
  bool renumbered = false;
};

// Renumbers points and tets on the calling thread's TBB arena; the result
// does not depend on the thread count. Non-finite points go last, in their
// old order. Adds a note to m.notes.
RenumberStats renumber_for_locality(TetMesh& m);

// The mean over tets of (largest - smallest point id), in units of
// points^(2/3) — the points of one slab of a cube of points, what a tet
// spans in a well-ordered numbering: ~1 for a grid in plain or Morton
// order, ~points^(1/3) / 3 for a shuffled one.
double id_spread(const TetMesh& m);

// The 63-bit Morton code of a point quantised to 21 bits per axis in [lo, hi].
uint64_t morton_code(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi);

}  // namespace zs
