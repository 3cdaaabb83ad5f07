// Which spheres a frame draws (spheres digest §2.2): view-volume culling of the grid's
// cells (p-vertex test, Algorithm 3.1), front-to-back occlusion culling of the
// surviving cells against the conservative centre-disc depth map
// (occlusion_map.h), and the one-level max-depth pyramid test per sphere.
// Every test is conservative — a sphere is dropped only when no pixel centre
// can see it — so the image is bit-identical with culling off.
//
// Cells are visited nearest first (by their box's nearest depth). A cell is
// tested against the map drawn from the cells visited before it; if it
// survives, its spheres' discs are drawn into the map. (The seed draws every
// surviving cell's discs first and then queries; testing as the map grows
// needs one pass and no queries, in the spirit of Grottel et al.)
#pragma once

#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "raster/sphere_span.h"
#include "geometry/spheres/sphere_set.h"
#include "render/spheres/sphere_grid.h"
#include "base/view/camera.h"

namespace zs {

struct VisibilityStats {
  uint64_t cells = 0, cells_empty = 0, cells_view_culled = 0, cells_occluded = 0;
  uint64_t spheres_view_culled = 0;      // in view-culled cells
  uint64_t spheres_occluded_cells = 0;   // in occluded cells
  uint64_t spheres_pyramid_culled = 0;   // dropped by the per-sphere test
  uint64_t spheres_pixel_culled = 0;     // small ones whose every exact hit lies behind the map
  uint64_t spheres_offscreen = 0;        // no pixel centre of the image in their silhouette (or its box)
  uint64_t occluders = 0;                // discs drawn into the map
  uint64_t spheres_visible = 0;          // what the frame draws
  double ms_view = 0, ms_occlusion = 0, ms_pyramid = 0;
  uint64_t map_bytes = 0;
};

// Spheres whose pixel box holds at most this many pixel centres are tried
// pixel by pixel instead of by rows (most spheres of a large set).
constexpr int kSmallSphereBox = 16;

// The screen mapping of a view, as the raster's sphere spans take it.
CameraPlane camera_plane(const View& view);

// A sphere in camera space (x along right, y along up, z the view depth).
inline glm::dvec3 to_camera(const View& v, const glm::dvec3& p) {
  const glm::dvec3 d = p - v.eye();
  return {glm::dot(d, v.right()), glm::dot(d, v.up()), glm::dot(d, v.forward())};
}

// The spheres to draw, as entries of the grid (indices into g.ids, g.centre,
// g.radius), cells nearest first. With culling off: every drawable sphere with
// a pixel centre in its silhouette's box.
// The per-sphere tests run on `threads` threads. `occluder` (per grid entry;
// null: every sphere): which spheres' discs may hide others — in the
// translucent modes only opaque ones do.
std::vector<uint32_t> visible_spheres(const SphereSet& s, const SphereGrid& g, const View& view, bool culling,
                                      VisibilityStats* stats, int threads = 1,
                                      const std::vector<uint8_t>* occluder = nullptr);

}  // namespace zs
