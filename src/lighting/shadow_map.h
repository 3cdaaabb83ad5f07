// A shadow map (shadow-maps digest §2.2) and its multiple-depth form, the
// n-SM (§2.6): the depths of the casters nearest to a light, rendered by the
// raster core's z-buffer over the map's own tiles, then one image-space pass
// that gives each texel n depths. Shared by the surface renderer and the
// sphere renderer's ambient occlusion (sphere_map.h); it knows triangles,
// lights and world points, nothing of either renderer.
//
// Frame: directional lights get an orthographic map whose square covers the
// receivers in view (fit_directional), spot lights a perspective map of the
// cone (full angle fov_deg inside the square). Depth is the light view's
// depth in world units (orthographic: along the light direction; spot:
// camera-space z), stored as float rounded upwards.
//
// Test (the shadow-maps digest's composite test, §2.6.2 and §2.6.4, and its
// PCF(k,n), §2.6.4, with a box kernel): a point p at light depth d is lit by
// a stored depth z when
//   d − bias_total ≤ z,   bias_total = bias + slope_bias·tanθ·w·(1 + R) + 2^-20·|d|
// with θ the angle between the surface normal and the light, tanθ clamped to
// 10, w the world size of a texel at p, R the farthest texel the test reads
// beyond p's own (PCF radius, plus one for min-selected or fixed-pattern
// depths; max-selected depths add nothing: they cannot self-shadow), and the
// last term the float storage. The lit count over the k kernel texels × n
// depths, out of k·n, is the lit fraction: at most n·k + 1 distinct levels.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/tets/tet_mesh.h"  // Bounds
#include "lighting/depth_blocks.h"
#include "lighting/light.h"
#include "lighting/shadow_settings.h"
#include "lighting/tiled_depths.h"
#include "geometry/triangles/triangle_mesh.h"
#include "base/view/camera.h"

namespace zs {

// The box, in a directional light's frame, of the receivers it must cover.
struct LightFit {
  glm::dvec3 r{1, 0, 0}, u{0, 1, 0}, f{0, 0, 1};  // frame: f = light direction
  double lo_r = INFINITY, hi_r = -INFINITY, lo_u = INFINITY, hi_u = -INFINITY;
  void add(const glm::dvec3& p);
  bool empty() const { return !(lo_r <= hi_r); }
};
LightFit start_fit(const Light& l);

struct ShadowMapStats {
  double ms_project = 0, ms_raster = 0, ms_multi_depth = 0;
  uint64_t casters = 0;         // triangles projected into the map
  uint64_t casters_culled = 0;  // left out: they can shadow no point (ShadowSettings::cull_casters)
  uint64_t casters_back_faces = 0;  // left out: faces of closed solids turned from a directional light
  uint64_t caster_fragments = 0;
  uint64_t texels_covered = 0;  // texels with a caster
  uint64_t bytes = 0;           // the map and its n-SM
  double texel = 0;             // world size of a texel (spot: per unit of depth)
  double side = 0;              // orthographic: world side of the map's square
};

// What a lookup needs of a map, in plain doubles (shadow_map.cpp): set once
// when the map is finished, copied into locals by each batch of lookups.
struct LookupFrame {
  double ex, ey, ez, fx, fy, fz, rx, ry, rz, ux, uy, uz;  // the light view (View::project)
  double sx, sy, ox, oy;
  double lx, ly, lz;  // directional: unit vector towards the light
  double bias, slope, texel, reach, D;
};

// A directional map's lookup inputs as affine functions of the world point
// p: map column X = x0 + x·p and row Y = y0 + y·p (before clamping), light
// depth z = z0 + z·p. Callers that know p as a function of something else
// (a camera pixel) compose these and call counts_at.
struct AffineLookup {
  double x0 = 0, y0 = 0, z0 = 0;
  glm::dvec3 x{0.0}, y{0.0}, z{0.0};
};

class ShadowMap {
 public:
  // Renders the casters (every triangle, both faces) from `light` on
  // `threads` threads. `fit`: the receivers to cover (directional lights;
  // ignored for spot lights). `scene`: the casters' bounds.
  static ShadowMap build(const TriangleMesh& casters, const Light& light, const LightFit& fit, const Bounds& scene,
                         const ShadowSettings& s, int threads, ShadowMapStats* stats = nullptr);
  // A map from depths already kept by tiles (a 1-depth map) in a given frame;
  // `blocks` are its block ranges when the caller folded them (else empty).
  static ShadowMap from_tiles(const Light& light, const Camera& frame, TiledDepths centre, const ShadowSettings& s,
                              DepthBlocks blocks = {});
  // A map from given depths (size·size, row-major; +inf = no caster) in a
  // given frame: tests and synthetic maps.
  static ShadowMap from_depths(const Light& light, const Camera& frame, uint32_t size, std::vector<float> depths,
                               const ShadowSettings& s);

  // Lit tests passed at world point p with unit normal n (facing the
  // viewer), out of levels(); 0 outside a spot light's cone or where n faces
  // away from the light. Thread-safe.
  uint32_t lit_count(const glm::dvec3& p, const glm::dvec3& n) const;
  uint32_t levels() const { return levels_; }  // k·n
  double lit(const glm::dvec3& p, const glm::dvec3& n) const { return double(lit_count(p, n)) / levels_; }
  // lit_count of n points at once (coordinates as arrays): the same counts,
  // with the arithmetic before the map reads vectorized across points.
  void lit_counts(size_t n, const double* px, const double* py, const double* pz, const double* nx, const double* ny,
                  const double* nz, uint32_t* out) const;

  // Directional maps: the inputs of a lookup as affine functions of p; the
  // bias's part that depends on the normal alone, at cos θ = c (NaN where
  // c ≤ 0: the face is turned from the light), so that p's limit is
  // lim = z − (face_bias(c) + |z|·2^-20) (the header comment's bias_total);
  // and the lit counts of n points given X, Y and lim (NaN: none lit), the
  // same counts lit_counts gives for the same inputs.
  AffineLookup affine_lookup() const;
  double face_bias(double c) const;
  void counts_at(size_t n, const double* X, const double* Y, const double* lim, uint32_t* out) const;
  // True when every lookup with X in [x0, x1] and Y in [y0, y1] reads only
  // texels of tiles with no caster (all +inf): counts_at then gives levels()
  // for a number limit and 0 for NaN, without reading. False for bounds that
  // are not finite.
  bool passes_all(double x0, double x1, double y0, double y1) const;

  // The texel a one-texel kernel reads for p (nearest, clamped to the map)
  // and p's test limit d − bias: what other per-texel data of the map (the
  // sphere AO's translucent lists) need.
  void locate(const glm::dvec3& p, const glm::dvec3& n, uint32_t* x, uint32_t* y, double* lim) const;

  // Texel (x, y)'s j-th depth (j < depths()); the n-SM as built.
  float depth(uint32_t x, uint32_t y, uint32_t j = 0) const { return md_.texel(x, y)[j]; }
  uint32_t size() const { return size_; }
  uint32_t depths() const { return n_; }
  const View& view() const { return *view_; }
  // The bias the test applies at p (world units), for tests and docs.
  double bias_at(const glm::dvec3& p, const glm::dvec3& n) const;
  // The kernel's texel offsets, relative to floor(X) or round(X) (see .cpp).
  uint64_t bytes() const { return md_.bytes() + blocks_.min.size() * 2 * sizeof(float); }
  uint32_t stored_tiles() const { return md_.stored_tiles(); }  // of the n-SM (tiled_depths.h)

 private:
  void finish(TiledDepths centre);  // builds the n-SM
  double bias_for(double d, double cos_theta) const;  // bias_at from p's light depth and |N·L|
  LookupFrame make_frame() const;  // the map's constants for a lookup (finish())
  uint32_t count(double X, double Y, double lim) const;
  static constexpr uint32_t kOpenClass = 0xffffffffu;  // block_classes: read the kernel
  void block_classes(size_t m, const double* __restrict X, const double* __restrict Y, const double* __restrict lim,
                     uint32_t* __restrict cls) const;
  Light light_;
  glm::dvec3 to_light_{0.0};  // directional: unit vector towards the light
  LookupFrame frame_{};
  ShadowSettings s_;
  std::shared_ptr<View> view_;
  uint32_t size_ = 0, n_ = 1, levels_ = 1;
  double texel_ = 0;   // orthographic: world size of a texel; spot: per unit depth
  double reach_ = 1;   // 1 + R of the header comment
  TiledDepths md_;         // the n-SM, by tiles
  DepthBlocks blocks_;     // exact early out of the test
};

// The frame of a map: directional lights an orthographic square covering
// `fit` (or the scene's box when fit is empty) plus a margin, its eye plane
// behind every caster; spot lights a perspective view of the cone.
// `z_near`: the depth below which geometry is clipped.
Camera shadow_map_frame(const Light& light, const LightFit& fit, const Bounds& scene, uint32_t size, double* z_near);

// Bytes a map of these settings holds (for budgets).
uint64_t shadow_map_bytes(const ShadowSettings& s);

}  // namespace zs
