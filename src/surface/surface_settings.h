// What a SurfaceRenderer takes (built from a surface scene, scene/scene.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "shadows/light.h"
#include "shadows/shadow_settings.h"
#include "surface/surface_shading.h"
#include "view/camera.h"

namespace zs {

struct SurfaceRenderSettings {
  uint32_t width = 512, height = 512, tile_size = 64;
  int threads = 1;
  Camera camera;
  std::array<double, 4> background{0, 0, 0, 0};  // premultiplied RGBA, where no surface is
  bool cull_back = true;   // back-face culling (default on, seed 003)
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
  uint64_t memory_budget_bytes = 0;  // 0: none
  bool progress = false;
};

}  // namespace zs
