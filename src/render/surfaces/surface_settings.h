// What a SurfaceRenderer takes (built from a surface scene, scene/scene.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting/light.h"
#include "lighting/shadow_settings.h"
#include "lighting/surface_shading.h"
#include "render/frame_settings.h"

namespace zs {

// The frame (size, background, camera, threads, tiles, budget) and the
// surfaces' own: culling, colours, lights, shading and shadows.
struct SurfaceRenderSettings : FrameSettings {
  bool cull_back = true;   // back-face culling (default on, as in seed 003's slides)
  bool cull_view = true;   // view-volume culling
  std::vector<glm::dvec3> colors;  // per surface id (mesh.surface)
  std::vector<Light> lights;
  SurfaceShading shading;
  ShadowSettings shadows;
  bool shadows_enabled = true;
  // The Z and lit channels of the tiles (off: R, G, B, A only, for outputs
  // that keep no more; the same colours either way).
  bool depth_and_lit = true;
  // The exact early out of directional lookups that fall in map tiles with
  // no caster (surface_renderer.cpp). Off only to show that it changes no bit.
  bool empty_tile_early_out = true;
};

}  // namespace zs
