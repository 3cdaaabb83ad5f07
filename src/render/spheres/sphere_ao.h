// The sphere renderer's ambient occlusion (docs/spheres.md, "Ambient
// occlusion"; spheres digest §2.4): the maps of a set for its settings, their memory
// bounds, and the AO of a tile's visible points, from the maps held or from
// the sums that batches of maps leave per image pixel.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "lighting/sphere_map.h"
#include "geometry/spheres/sphere_set.h"
#include "render/spheres/sphere_settings.h"
#include "base/view/camera.h"

namespace zs {

// The maps of directions `dirs` for settings.ao (bias defaults resolved).
// `colors`: the spheres' colours, whose alpha the "alpha" occluders use.
SphereAoMaps build_sphere_ao(const SphereSet& s, const std::vector<glm::vec4>& colors, const SphereRenderSettings& rs,
                             const std::vector<glm::dvec3>& dirs);
// Every direction's maps, or null when they cannot all be held in
// `available` bytes (the renderer then builds them in batches each frame).
// Opaque occluders are checked against their bound before any is built;
// alpha ones (their lists have no bound) as they are built.
std::shared_ptr<const SphereAoMaps> sphere_ao_maps(const SphereSet& s, const std::vector<glm::vec4>& colors,
                                                   const SphereRenderSettings& rs, uint64_t available);
// The most memory one AO map's depths take, and all of them.
uint64_t sphere_ao_map_bytes_bound(const SphereRenderSettings& rs);
uint64_t sphere_ao_bytes_bound(const SphereRenderSettings& rs);
// Batches (the seed's several passes when the maps outnumber the texture
// units, spheres digest §2.4.6): per frame, the image's AO sums (this many bytes), and as
// many maps at once as the rest of the budget holds after `held` bytes
// (alpha occluders: at most one per thread, their lists checked as built).
// Throws, in one line, when even one map does not fit, or for a translucent
// render.mode (its fragments need every map at once).
uint64_t sphere_ao_sums_bytes(const SphereRenderSettings& rs);
uint32_t sphere_ao_batch_size(const SphereRenderSettings& rs, uint64_t budget, uint64_t held, int threads);

// A surface point in camera space (x right, y up, z forward) and its unit
// normal in view space (z towards the viewer), in world space: where the
// maps are looked up.
inline void ao_world(const View& view, const glm::dvec3& P, const glm::dvec3& n, glm::dvec3* Pw, glm::dvec3* Nw) {
  *Pw = view.eye() + P.x * view.right() + P.y * view.up() + P.z * view.forward();
  *Nw = glm::normalize(n.x * view.right() + n.y * view.up() - n.z * view.forward());
}

// A tile's visible points for AO: image pixel, world position and unit
// normal (as arrays, for accumulate_ao), and their sums.
struct AoPoints {
  std::vector<size_t> pixel;
  std::vector<double> px, py, pz, nx, ny, nz, num, den;
  void clear();
  void add(size_t image_pixel, const glm::dvec3& p, const glm::dvec3& n);
  size_t size() const { return pixel.size(); }
  double ao(size_t i) const { return den[i] > 0 ? num[i] / den[i] : 1.0; }
};

// The points' sums over every direction: from the maps `held`, or (null)
// from the numerators batches left in `image_sums` with the weights over
// `dirs` again, in the same direction order: the same sums either way.
void ao_sums(AoPoints& pts, const SphereAoMaps* held, const std::vector<glm::dvec3>& dirs,
             const std::vector<double>& image_sums);
// One batch's terms added to the numerators in `image_sums`.
void add_ao_batch(AoPoints& pts, const SphereAoMaps& batch, std::vector<double>& image_sums);

}  // namespace zs
