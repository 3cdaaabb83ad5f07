// The ground truth for every error figure in the project: an independent ray
// caster. One ray per pixel centre (the scene spec's rays, camera.h), exact
// line–tet intersections by walking the face adjacency (tet_walk.h), entering
// at boundary faces and re-entering non-convex meshes at the next boundary
// entry (boundary_hits.h), and the scalar linear along each piece, integrated
// exactly (split at transfer-function breakpoints, closed-form optical depth,
// adaptive quadrature for colour: segment_integrator.h).
//
// It shares the camera, the transfer function and the segment optics (base/)
// with the ZSweep engine, and hands back the raster core's Image; nothing of
// the engine's sweep, scan conversion, fragment lists or compositor.
#pragma once

#include <cstdint>
#include <vector>

#include "base/optics/transfer_function.h"
#include "geometry/tets/tet_mesh.h"
#include "geometry/tets/topology.h"
#include "raster/image.h"
#include "render/frame_settings.h"

namespace zs {

struct ReferenceStats {
  double ms_total = 0;
  uint64_t rays_hit = 0;        // rays that entered the mesh in front of the eye
  uint64_t segments = 0;        // tet pieces integrated
  uint64_t tet_steps = 0;       // tets visited (including behind the eye)
  uint64_t entries = 0;         // walks started at a boundary entry
  uint64_t segments_clipped = 0;  // segments cut or dropped by the clip planes
  uint64_t rays_stopped = 0;    // mixed scenes: rays through the mesh that meet opaque geometry
  uint64_t lost_walks = 0;      // walks that found no exit (the rest of that line re-enters at the next boundary face)
  uint64_t flat_tets = 0;       // zero-volume tets, left out of the solid mesh
  uint64_t boundary_faces = 0, unbinned_faces = 0;
};

// Opaque geometry under the volume (mixed scenes), per pixel of the whole
// image: its colour over the background and its view depth (+inf: none).
// Each ray stops at that depth and the volume is composited over the colour.
struct ReferenceUnder {
  const Image* rgba = nullptr;
  const float* z = nullptr;
};

// Honours width, height, camera, background, clip planes, transfer function
// and threads; the integrator is always exact, and no early termination is
// applied.
Image render_reference(const TetMesh& mesh, const Topology& topo, const FrameSettings& frame,
                       const TransferFunction& tf, ReferenceStats* stats, const ReferenceUnder* under = nullptr);
// Only the listed rows of the full image (row k of the result is image row
// rows[k]): checks of huge renders sample rows instead of casting every ray.
Image render_reference_rows(const TetMesh& mesh, const Topology& topo, const FrameSettings& frame,
                            const TransferFunction& tf, const std::vector<uint32_t>& rows,
                            ReferenceStats* stats, const ReferenceUnder* under = nullptr);

}  // namespace zs
