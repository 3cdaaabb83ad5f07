// "Model only what the scene requires": which tets can contribute light, and
// what each face is to a ray coming from the eye.
//
// A tet is visible unless it is degenerate (zero volume, non-finite), its
// whole scalar range maps to zero opacity (with absorption plus emission,
// such a tet neither attenuates nor emits), or the scene's clip planes keep
// none of it: dropping any of these is exact. Faces are
// then classified against the visible subset of the mesh:
//   culled   — no visible tet on either side: no fragments at all;
//   interior — visible on both sides;
//   entry    — one visible side, lying behind the face as seen from the eye;
//   exit     — one visible side, in front of the face.
// Entry/exit drive the compositor's inside count (compositor.h), which keeps
// gaps of non-convex meshes (and of invisible regions) dark.
//
// Cell data (one value per tet) are constant inside a tet and jump at its
// faces. A fragment then carries the value of the tet the ray enters through
// its face (for an exit face, the visible tet), and the compositor holds each
// segment at its front fragment's value. The class byte says which of the
// face's two tets that is (kValueTet1); with point data it is never set.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "base/view/camera.h"
#include "base/view/clip_region.h"
#include "base/optics/transfer_function.h"

namespace zs {

enum class FaceClass : uint8_t { Culled, Interior, Entry, Exit };
constexpr uint8_t kValueTet1 = 4;  // cell data: the face's fragments take tet1's value (else tet0's)
inline FaceClass base_class(FaceClass c) { return FaceClass(uint8_t(c) & 3); }
inline bool value_from_tet1(FaceClass c) { return (uint8_t(c) & kValueTet1) != 0; }

struct FaceClassCounts {
  uint64_t tets_invisible = 0;   // scalar range with zero opacity
  uint64_t tets_degenerate = 0;  // zero volume or non-finite
  uint64_t faces_culled = 0;
  uint64_t cell_data_tets = 0;  // visible tets rendered with their own (cell) value
  uint64_t tets_clipped = 0;    // wholly outside a clip plane
};

// tet_visible (optional) receives one byte per tet; on_visible (optional)
// one byte per point: 1 on a vertex of a visible tet, which is a vertex of a
// face that is not culled (the sweep's events). Runs on the calling thread's
// TBB arena.
std::vector<FaceClass> classify_faces(const TetMesh& m, const Topology& topo, const TransferFunction& tf,
                                      const View& view, FaceClassCounts* counts,
                                      std::vector<uint8_t>* tet_visible = nullptr,
                                      std::vector<uint8_t>* on_visible = nullptr,
                                      std::vector<FaceClass> storage = {}, const ClipRegion* clip = nullptr);

}  // namespace zs
