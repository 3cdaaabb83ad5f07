// The part of each triangle inside a view's frustum (the image's pixel
// footprint, at depth >= z_near), as world points: what a directional
// light's shadow map must cover (lighting/shadow_map.h, LightFit). Hidden
// parts are included, so the region holds every visible point.
#pragma once

#include <functional>

#include <glm/vec3.hpp>

#include "geometry/triangles/triangle_mesh.h"
#include "base/view/camera.h"

namespace zs {

// Calls `point` with every corner of every triangle's clipped polygon;
// `cull_back`: skip one-sided triangles whose back faces the eye (they are
// invisible; TriangleMesh::two_sided ones are not).
void visible_region_points(const TriangleMesh& m, const View& view, double z_near, bool cull_back,
                           const std::function<void(const glm::dvec3&)>& point);

}  // namespace zs
