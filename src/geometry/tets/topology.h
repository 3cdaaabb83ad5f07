// Face topology of a tet mesh, built once: the unique triangular faces, the
// one or two tets on each, the boundary flag, and each vertex's use set (the
// unique faces incident to it — what the ZSweep sweep projects when it passes
// the vertex; B-Convert digest §1.1).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/tets/tet_mesh.h"

namespace zs {

constexpr uint32_t kNoTet = UINT32_MAX;

struct Topology {
  // Unique faces, vertex indices sorted ascending.
  std::vector<std::array<uint32_t, 3>> faces;
  // The tets on each face: [0] always valid, [1] = kNoTet on a boundary face.
  // Faces shared by more than two tets (non-manifold) keep the first two here
  // and are listed in `nonmanifold_faces`.
  std::vector<std::array<uint32_t, 2>> face_tets;
  std::vector<uint32_t> nonmanifold_faces;
  // Per tet, its four face ids; face k is the one opposite local vertex k.
  std::vector<std::array<uint32_t, 4>> tet_faces;
  // Use sets in compressed rows: faces of vertex v are
  // use_faces[use_offsets[v] .. use_offsets[v+1]).
  std::vector<uint32_t> use_offsets;
  std::vector<uint32_t> use_faces;
  size_t num_boundary_faces = 0;
  // Per tet, what culling asks of it whatever the view and transfer function
  // (render/volume/face_classes.h), computed once here from the mesh's points and
  // scalars (rebuild the topology if they change): degenerate (zero volume by
  // validation's relative criterion, or a non-finite point or scalar), and the
  // scalar range over its four vertices.
  std::vector<uint8_t> tet_degenerate;
  std::vector<std::array<double, 2>> tet_scalar_range;

  size_t num_faces() const { return faces.size(); }
  bool is_boundary(uint32_t f) const { return face_tets[f][1] == kNoTet; }
  std::span<const uint32_t> use_set(uint32_t v) const {
    return {use_faces.data() + use_offsets[v], use_faces.data() + use_offsets[v + 1]};
  }
};

Topology build_topology(const TetMesh& m);

}  // namespace zs
