// A triangle surface cut by a scene's clip region (base/view/clip_region.h),
// in world space, once at load: what the planes do not keep is gone for the
// render, its shadows and its reference alike, and a closed solid that is cut
// becomes open (its inside shows through the cut, which adds no surface of its
// own). Sutherland–Hodgman against each plane; a cut point is made once per
// (edge, plane) and shared by the triangles on that edge, computed from the
// edge's endpoints in id order, so a cut surface stays watertight.
#pragma once

#include <cstddef>

#include "base/view/clip_region.h"
#include "geometry/triangles/triangle_mesh.h"

namespace zs {

struct TriangleClipCounts {
  size_t dropped = 0;  // triangles wholly outside
  size_t cut = 0;      // triangles cut by a plane
};

// Keeps each triangle's surface id; drops `normals`, `solid` and `two_sided`
// (worked out again after the cut).
TriangleClipCounts clip_triangles(TriangleMesh& m, const ClipRegion& region);

}  // namespace zs
