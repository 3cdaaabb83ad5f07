// Orthographic shadow maps of sphere sets, one per ambient-occlusion
// direction (spheres digest §2.4.5), and the AO they give a point (§2.4.6).
//
// A map looks along −ω (light arriving from ω) and is fitted to the set's
// bounding box rotated into that frame, so it covers the whole set whatever
// the viewer. Each sphere is drawn as
//   - its centre disc (Tarini et al.'s trick, the default): the silhouette
//     disc at the centre's depth. A point on a sphere that faces ω is always
//     in front of its own disc, so it cannot shadow itself; or
//   - its impostor: the exact front surface, depth c − √(r² − ρ²). Tighter
//     for thin gaps, but a point near its own silhouette reads the nearer
//     surface of neighbouring texels: it needs a slope bias.
// For spheres that do not overlap, a point on one sphere is blocked by
// another's disc exactly when the ray towards ω meets that sphere, so both
// converge to exact visibility as the map grows.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting/shadow_map.h"
#include "lighting/transmittance_lists.h"

namespace zs {

enum class SphereDepth { CentreDisc, Impostor };
struct SphereMapScratch;  // a thread's buffers, reused from map to map

struct SphereMapStats {
  double ms = 0;
  uint64_t texels_written = 0;  // disc texels, over all spheres
};

// The map for direction `omega` (unit, towards the light) of spheres
// (centres, radii), `size`² texels; `s` gives the bias (world units) for the
// lookups (depths and pcf are used as given, normally 1 and 1).
// `alpha` (one opacity per sphere; null: every sphere opaque): spheres of
// alpha >= 1 go into the depths, 0 < alpha < 1 into `translucent` (needed
// then), and the rest into neither.
ShadowMap build_sphere_map(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii,
                           const glm::dvec3& omega, uint32_t size, SphereDepth mode, const ShadowSettings& s,
                           int threads, SphereMapStats* stats = nullptr, const std::vector<float>* alpha = nullptr,
                           TransmittanceLists* translucent = nullptr, SphereMapScratch* scratch = nullptr);

// Every direction's map for a sphere set: the AO preprocessing (§2.4.5),
// built once and reused by every frame of a static set. Maps are built in
// parallel over directions (each one by one thread) when there are at least
// as many directions as threads, else one after another over tiles; the maps
// are the same either way.
// With `alpha` (occluders "alpha"), each map also has its translucent lists.
struct SphereAoMaps {
  std::vector<glm::dvec3> dirs;
  std::vector<ShadowMap> maps;
  std::vector<TransmittanceLists> translucent;  // one per map, or none (opaque occluders)
  double ms_build = 0;
  uint64_t bytes = 0;
  uint64_t translucent_fragments = 0;
};
SphereAoMaps build_sphere_ao_maps(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii,
                                  const std::vector<glm::dvec3>& dirs, uint32_t size, SphereDepth mode,
                                  const ShadowSettings& s, int threads, const std::vector<float>* alpha = nullptr);

// AO(P) = Σ_k V_k(P)·max(0, N·ω_k) / Σ_k max(0, N·ω_k), V_k the lit fraction
// of map k (built for dirs[k]) times, with translucent lists, the
// transmittance Π(1 − α) of the translucent discs between P and the light;
// N unit. 1 when no direction faces N.
double ambient_occlusion(const SphereAoMaps& ao, const glm::dvec3& p, const glm::dvec3& n);
// The sums of that formula for n points (world positions and unit normals as
// arrays) over this set's directions, added to num and den in direction
// order: a set of maps can be consumed in batches, and every batch adds the
// same terms the whole set would.
void accumulate_ao(const SphereAoMaps& ao, size_t n, const double* px, const double* py, const double* pz,
                   const double* nx, const double* ny, const double* nz, double* num, double* den);
// The denominators alone (no map read), the same sums accumulate_ao adds.
void ao_weights(const std::vector<glm::dvec3>& dirs, size_t n, const double* nx, const double* ny, const double* nz,
                double* den);

}  // namespace zs
