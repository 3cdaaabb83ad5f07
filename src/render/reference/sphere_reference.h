// Ground truth for the sphere renderers: an independent ray tracer for sphere
// sets. Embree (float) finds candidates in a BVH of slightly enlarged
// spheres; every candidate is then intersected exactly in double with the
// SphereSet's own centre and radius along View::ray's double ray, so the
// reported hits do not depend on Embree's float arithmetic.
//
// Only surfaces at positive distance along the ray count: when the ray
// starts inside a sphere (perspective eye inside it, or the orthographic eye
// plane cutting it) its visible surface is the exit. Depths are VIEW depths
// (distance along View::forward() from the eye, as View::depth()).
//
// It shares the view, sphere colours and shading (lighting/shading_model.h)
// with the sphere renderers, and nothing of their rasterisation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "raster/image.h"
#include "geometry/spheres/sphere_set.h"
#include "lighting/shading_model.h"
#include "base/view/camera.h"

namespace zs {

// One surface crossing along a ray: view depth, sphere index in the set, and
// whether the ray enters (front surface) or leaves (back surface) the sphere.
struct SphereCrossing {
  double depth;
  uint32_t id;
  bool entering;
};

class SphereReference {
 public:
  // Builds the BVH (Embree's own threads; `threads` > 0 limits them, 0: all
  // cores). Throws std::runtime_error on Embree errors and when a sphere's
  // coordinates do not fit in a float.
  SphereReference(const SphereSet& spheres, const View& view, int threads = 0);
  ~SphereReference();
  SphereReference(const SphereReference&) = delete;
  SphereReference& operator=(const SphereReference&) = delete;

  // The nearest visible surface along the ray through pixel coordinates
  // (X, Y) (X = i for the centre of column i): its view depth, the sphere's
  // index (equal depths: the smaller index) and the unit normal facing the
  // viewer in view space (x right, y up, z towards the viewer). False when
  // the ray hits nothing in front of it. Thread-safe; no heap allocation.
  bool nearest(double X, double Y, double* depth, uint32_t* id, glm::dvec3* normal_view) const;
  // Every surface crossing at positive distance along that ray, sorted by
  // depth, then index, entering before leaving (a tangent ray gives both at
  // one depth). `out` is cleared first. Thread-safe.
  void crossings(double X, double Y, std::vector<SphereCrossing>* out) const;
  // The same along any ray o + t·u (u unit), with `depth` the ray parameter t.
  void ray_crossings(const glm::dvec3& o, const glm::dvec3& u, std::vector<SphereCrossing>* out) const;
  // Whether a sphere other than set index `skip` has a surface at t > 0 on
  // that ray: true exactly when ray_crossings would list one. An any-hit
  // query (Embree stops at the first), so it does not grow with the number
  // of spheres the ray crosses. Thread-safe; no heap allocation.
  bool ray_blocked(const glm::dvec3& o, const glm::dvec3& u, uint32_t skip) const;

  // Spheres left out: non-finite centre, radius not positive or not finite.
  size_t invalid() const { return invalid_; }
  // The radius margin the float BVH adds (world units), for reports.
  double margin() const { return margin_; }

  struct Impl;  // Embree state (the filter callbacks need it)

 private:
  std::unique_ptr<Impl> impl_;
  size_t invalid_ = 0;
  double margin_ = 0;
};

struct SphereReferenceImage {
  Image rgba;            // premultiplied; alpha 1 where a sphere is hit
  std::vector<float> z;  // view depth per pixel (row 0 top), +inf where nothing is hit
  double ms_build = 0, ms_trace = 0;
  uint64_t hits = 0;     // pixels that hit a sphere
  size_t invalid = 0;    // spheres left out (SphereReference::invalid())
};

// Nearest mode at every pixel centre: colour = shade(shading, rgb of the
// sphere's colour, n, v) with n the visible surface's normal facing the
// viewer and v the unit vector towards the eye, alpha 1; `background`
// (premultiplied RGBA) elsewhere. `colors`: one per sphere (sphere_colors());
// their alpha is ignored (opaque). threads <= 0: all cores; 1: this thread only.
SphereReferenceImage render_sphere_reference(const SphereSet& spheres, const std::vector<glm::vec4>& colors,
                                             const Shading& shading, const View& view, const double background[4],
                                             int threads);

// Translucent scenes: every crossing of the ray (with `front_only`, each
// sphere's first one: its visible surface), in depth order, composited front
// to back (premultiplied, colour shaded at the crossing with the normal
// facing the viewer, the sphere's alpha; alpha 0 adds nothing, an alpha-1
// sphere ends the ray) over `background`; no early stop, no layer cap. Z:
// the nearest crossing of a sphere with alpha > 0. The exact answer the
// translucent modes are measured against. With `ao` (below): each crossing's
// colour × its AO, taken with the sphere's outward normal; `ao_out` per
// pixel: the nearest crossing's AO (+inf where none).
struct SphereAoSpec;
SphereReferenceImage render_sphere_reference_translucent(const SphereSet& spheres,
                                                         const std::vector<glm::vec4>& colors, const Shading& shading,
                                                         const View& view, const double background[4], int threads,
                                                         bool front_only, const SphereAoSpec* ao = nullptr,
                                                         std::vector<float>* ao_out = nullptr);

// Ambient occlusion by exact rays (no map): with samples = 0 over `dirs`
// (the renderer's directions and weights, isolating the maps' error), else
// a cosine-weighted Monte Carlo estimate with that many rays per point (a
// fixed random stream per pixel; isolating the direction count's error).
// `alpha_occluders`: a sphere the ray crosses passes 1 − alpha of the light
// (the colours' alpha) instead of none.
struct SphereAoSpec {
  std::vector<glm::dvec3> dirs;
  uint32_t samples = 0;
  bool alpha_occluders = false;
};

// Opaque scenes with AO: the nearest surface as above, colour = AO ×
// shaded; `ao` per pixel, +inf where nothing is hit.
SphereReferenceImage render_sphere_reference_ao(const SphereSet& spheres, const std::vector<glm::vec4>& colors,
                                                const Shading& shading, const View& view, const double background[4],
                                                int threads, const SphereAoSpec& spec, std::vector<float>* ao);

}  // namespace zs
