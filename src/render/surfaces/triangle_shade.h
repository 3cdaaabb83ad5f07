// Per-triangle shading set-up of one view: what the deferred pass needs to
// resolve a pixel the triangle won, as functions of the pixel's camera-plane
// coordinates (a, b) (a = (X − ox)/sx, b = (oy − Y)/sy), so a pixel costs a
// few multiply-adds and one division instead of a ray–triangle intersection.
//
// Perspective: the pixel's ray is E + s·w with w = F + a·R + b·U, and its
// plane hit is at view depth s = K/(α + β·a + γ·b) (K = g·(A − E),
// (α, β, γ) = g·(F, R, U)). Orthographic: E + a·R + b·U + t·F with
// t = (K − β·a − γ·b)/α. Both are num(a, b)/den(a, b), numerator and
// denominator linear in (a, b). The barycentrics of the hit, hence the
// interpolated (Phong) normal times den, are linear in (a, b) too, so the
// shading normal is normalize(M0 + M1·a + M2·b) once den's sign (constant
// over a triangle in front of the eye) is folded into M.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting/shading_model.h"  // ShadingModel
#include "geometry/triangles/triangle_mesh.h"
#include "base/view/camera.h"

namespace zs {

struct TriangleShade {
  double num[3], den[3];  // view depth = (num0 + num1·a + num2·b)/(den0 + den1·a + den2·b)
  double g[3];            // unit face normal, turned to the eye
  double m[3][3];         // m[j]: coefficient of (1, a, b)[j] of the shading normal (unit at the centroid)
  float color[3];
};

// Set-up of mesh triangle t in `view`; flat shading gives m = (g, 0, 0).
TriangleShade triangle_shade(const TriangleMesh& mesh, uint32_t t, const View& view, ShadingModel model,
                             const glm::dvec3& color);

// Set-ups of the triangles `source[i]` (the projected triangles' mesh
// triangles), in parallel on `threads`.
void triangle_shades(const TriangleMesh& mesh, const std::vector<uint32_t>& source, const View& view,
                     ShadingModel model, const std::vector<glm::dvec3>& colors, int threads,
                     std::vector<TriangleShade>* out);

}  // namespace zs
