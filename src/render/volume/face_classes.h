// "Model only what the scene requires": which tets can contribute light, and
// what each face is to a ray coming from the eye.
//
// A tet is visible unless it is degenerate (zero volume, non-finite) or its
// whole scalar range maps to zero opacity: with absorption plus emission,
// such a tet neither attenuates nor emits, so dropping it is exact. Faces are
// then classified against the visible subset of the mesh:
//   culled   — no visible tet on either side: no fragments at all;
//   interior — visible on both sides;
//   entry    — one visible side, lying behind the face as seen from the eye;
//   exit     — one visible side, in front of the face.
// Entry/exit drive the compositor's inside count (compositor.h), which keeps
// gaps of non-convex meshes (and of invisible regions) dark.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "base/view/camera.h"
#include "base/optics/transfer_function.h"

namespace zs {

enum class FaceClass : uint8_t { Culled, Interior, Entry, Exit };

struct FaceClassCounts {
  uint64_t tets_invisible = 0;   // scalar range with zero opacity
  uint64_t tets_degenerate = 0;  // zero volume or non-finite
  uint64_t faces_culled = 0;
};

// tet_visible (optional) receives one byte per tet; on_visible (optional)
// one byte per point: 1 on a vertex of a visible tet, which is a vertex of a
// face that is not culled (the sweep's events). Runs on the calling thread's
// TBB arena.
std::vector<FaceClass> classify_faces(const TetMesh& m, const Topology& topo, const TransferFunction& tf,
                                      const View& view, FaceClassCounts* counts,
                                      std::vector<uint8_t>* tet_visible = nullptr,
                                      std::vector<uint8_t>* on_visible = nullptr,
                                      std::vector<FaceClass> storage = {});

}  // namespace zs
