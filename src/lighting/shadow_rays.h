// Hard shadows by shadow rays (the `exact` shadow mode, the maps' ground
// truth): one occlusion ray per visible point and light on Embree's BVH of
// the scene's triangles (both faces block). The same rules as the maps
// (shadow_map.h): a point whose normal faces away from the light, or outside
// a spot light's cone, is unlit.
//
// Precision: Embree tests in float, on coordinates taken relative to the
// scene's centre; the ray starts 1e-6 of the scene diagonal off the surface
// along its normal, so a surface never shadows itself. Shadow edges are thus
// exact to about 1e-6 of the scene size, far below a pixel in any image here.
#pragma once

#include <memory>

#include <glm/vec3.hpp>

#include "lighting/light.h"
#include "geometry/triangles/triangle_mesh.h"

namespace zs {

class ShadowRays {
 public:
  // Builds the BVH on `threads` threads (0: Embree's default).
  ShadowRays(const TriangleMesh& m, int threads);
  ~ShadowRays();
  ShadowRays(const ShadowRays&) = delete;
  ShadowRays& operator=(const ShadowRays&) = delete;
  // 1 when light l reaches p (unit normal n facing the viewer), else 0.
  // Thread-safe.
  bool lit(const Light& l, const glm::dvec3& p, const glm::dvec3& n) const;
  double ms_build() const;
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace zs
