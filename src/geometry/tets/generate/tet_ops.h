// Small whole-mesh operations every generator finishes with: consistent
// positive orientation, dropping degenerate tets, boundary extraction.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/tets/tet_mesh.h"

namespace zs {

// Swaps two vertices of every tet with signed_volume6 < 0.
void orient_positive(TetMesh& m);

// Removes tets with |6V| <= rel_eps * (longest edge)^3 and points no tet uses
// (scalars follow their points). Returns the number of tets removed.
size_t remove_degenerate(TetMesh& m, double rel_eps = 1e-12);

// Faces used by exactly one tet, wound so their normal points out of that tet
// (for a positively oriented mesh: out of the domain).
std::vector<std::array<uint32_t, 3>> boundary_faces(const TetMesh& m);

// Sum of tet volumes (absolute).
double total_volume(const TetMesh& m);

// orient_positive + remove_degenerate; throws std::runtime_error if the mesh
// ends up empty. Every generator's output goes through this.
void finalize_generated(TetMesh& m);

}  // namespace zs
