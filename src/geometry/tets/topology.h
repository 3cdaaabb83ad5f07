// Face topology of a tet mesh, built once per mesh and shared by every frame:
// the unique triangular faces, the one or two tets on each, the boundary
// flag, and each tet's degenerate flag. The sweep projects each face when the
// plane passes its first vertex (B-Convert digest §1.1-1.2); it needs no
// per-vertex use sets, so none are stored.
//
// Memory is the design at scale (docs/scaling.md): a face is 8 bytes — the
// tet it was first found in with which of that tet's faces it is, and the
// other tet — and its vertices are read back from that tet, so the topology
// costs about 17 bytes per tet on a 5-tet grid split (faces ≈ 2.1 × tets),
// plus 1 for the degenerate flag.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "base/util/uninit_vector.h"
#include "geometry/tets/tet_mesh.h"

namespace zs {

constexpr uint32_t kNoTet = UINT32_MAX;
// Tets are numbered in 30 bits: a face stores its first tet and local face
// index in one word.
constexpr uint64_t kMaxTopologyTets = uint64_t(1) << 30;

// The tets on one face: `first` = tet << 2 | k, where the face is the one
// opposite local vertex k of that tet; `second` = the other tet, kNoTet on a
// boundary face.
struct FaceTets {
  uint32_t first, second;
};

struct Topology {
  // Unique faces in the order of their sorted vertex triples. Faces shared by
  // more than two tets (non-manifold) keep the first two (lowest tet ids)
  // and are listed in `nonmanifold_faces`.
  UninitVector<FaceTets> face_tets;  // written in full by the build
  std::vector<uint32_t> nonmanifold_faces;
  size_t num_boundary_faces = 0;
  // Per tet, whether it is degenerate whatever the view and transfer
  // function: zero volume by validation's relative criterion, or a
  // non-finite point or scalar (render/volume/face_classes.h).
  std::vector<uint8_t> tet_degenerate;
  size_t num_nonfinite_tets = 0;  // of those, the ones with a non-finite point or scalar
  // The mesh's tets the faces point into: the topology is valid while they
  // live and are unchanged (rebuild it if the points, scalars or tets change).
  std::span<const Tet> tets;

  size_t num_faces() const { return face_tets.size(); }
  bool is_boundary(uint32_t f) const { return face_tets[f].second == kNoTet; }
  uint32_t tet0(uint32_t f) const { return face_tets[f].first >> 2; }
  uint32_t tet1(uint32_t f) const { return face_tets[f].second; }
  // Face f's vertex ids, ascending.
  std::array<uint32_t, 3> face(uint32_t f) const {
    const FaceTets& ft = face_tets[f];
    return tet_face(tets[ft.first >> 2], ft.first & 3);
  }
  // Face k of tet t (opposite local vertex k), vertex ids ascending.
  static std::array<uint32_t, 3> tet_face(const Tet& t, uint32_t k) {
    static constexpr uint8_t kOther[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    uint32_t a = t[kOther[k][0]], b = t[kOther[k][1]], c = t[kOther[k][2]];
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return {a, b, c};
  }
};

// Builds the topology on the calling thread's TBB arena (all its threads);
// the result does not depend on the thread count. Throws std::runtime_error
// for meshes of kMaxTopologyTets tets or more.
Topology build_topology(const TetMesh& m);

// Each tet's four face ids (face k opposite local vertex k), for the
// reference ray caster's tet walk; 16 bytes per tet, built on demand.
std::vector<std::array<uint32_t, 4>> build_tet_faces(const TetMesh& m, const Topology& topo);

// Bytes the topology of a mesh of `tets` tets holds, and the most the build
// holds at once on top of the mesh (faces estimated at 2.1 per tet, the
// 5-tet grid split's ratio; meshes with more boundary have fewer).
uint64_t topology_bytes(uint64_t tets);
uint64_t topology_build_peak_bytes(uint64_t points, uint64_t tets);

}  // namespace zs
