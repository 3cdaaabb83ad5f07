// The scene's `shadows` block (docs/shadows.md): how the shadow maps are
// built and sampled, or that shadow rays are traced instead.
#pragma once

#include <cstdint>
#include <string>

namespace zs {

// Which extra depth a 2-SM keeps from a texel's 3×3 neighbourhood
// (shadow-maps digest §2.6.5): the maximum (the half-tone band inside the
// classic shadow; cannot add self-shadowing) or the minimum (the band outside
// it).
enum class DepthSelect { Max, Min };
// `map`: shadow maps; `exact`: a shadow ray per pixel and light (Embree).
enum class ShadowMode { Map, Exact };

struct ShadowSettings {
  uint32_t map_size = 2048;   // texels per side
  double bias = 0.0;          // constant, world units
  double slope_bias = 1.5;    // texels of depth slope (see shadow_map.h)
  uint32_t depths = 1;        // n of n-SM, 1..9
  DepthSelect select = DepthSelect::Max;  // 2-SM only
  uint32_t pcf = 1;           // k: 1, 4, 9 or 16 texels
  ShadowMode mode = ShadowMode::Map;
  // Leave out of the maps the triangles that can shadow nothing: the whole
  // scene lies on their light side (shadow_map.h); and, for directional
  // lights, the faces of closed solids turned from the light (the nearest
  // caster along a light ray is never one: geometry/triangles/closed_solids.h). Exact
  // up to ties at texel centres on a solid's silhouette; off only to measure.
  bool cull_casters = true;
};

const char* to_string(DepthSelect s);
const char* to_string(ShadowMode m);

}  // namespace zs
