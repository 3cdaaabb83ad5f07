// Loading and framing a surface scene (scene_input.h's part for surfaces).
#pragma once

#include "scene/scene_input.h"

namespace zs {

// Reads every surface, applies its transform, turns closed solids wound
// inward outward and marks every other triangle two-sided (closed_solids.h),
// appends the ground square and computes point normals into in.surface. The
// ground is a square of side 4× the surfaces' largest horizontal extent
// (x, z), centred under them, at ground.height or (automatic) the surfaces'
// lowest y, a clear gap lower under a mesh lying flat there
// (ground_height.h), facing +y and one-sided. A surface whose path is a key
// of `data` is that mesh instead of a file.
void load_surfaces(SceneInput& in, const std::map<std::string, TriangleMesh>* data = nullptr);

// Perspective (or the given projection) camera looking at the surfaces'
// bounds obliquely from above and in front (direction (0.6, 0.5, 1)), y up,
// the whole bounding sphere in view.
Camera frame_surfaces(const Bounds& b, Projection projection, uint32_t width, uint32_t height);

}  // namespace zs
