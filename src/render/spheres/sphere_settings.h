// What a sphere render needs besides the spheres and their colours: the
// view, the image, the lighting, and the visibility switches (the scene's
// `image`, `camera`, `shading` and `render` blocks; docs/spheres.md).
#pragma once

#include <cstdint>
#include <string>

#include "lighting/shading_model.h"
#include "render/frame_settings.h"

namespace zs {

// How fragments are resolved (docs/spheres.md): the nearest surface wins
// (Opaque), or every surface is composited front to back with the sphere's
// alpha — exactly (Sorted), by the seed's depth peeling (Peel, DualPeel) or
// by Meshkin's order-independent weighted sum (Weighted).
enum class SphereMode { Opaque, Sorted, Peel, DualPeel, Weighted };
const char* to_string(SphereMode m);
bool parse_sphere_mode(const std::string& s, SphereMode* out);

// Ambient occlusion (spheres digest §2.4; docs/spheres.md): one orthographic
// map per direction, AO per visible pixel. Off when directions is 0.
struct SphereAo {
  uint32_t directions = 0;  // 6, 18, 66, 258, ... (lighting/ao_directions.h)
  uint32_t map_size = 1024;
  double bias = -1;         // world units; < 0: 1 % of the smallest radius
  bool impostor_depth = false;  // maps of exact front surfaces instead of centre discs
  bool alpha_occluders = false; // occluders "alpha": a sphere passes 1 − alpha of the light
  // Set when the maps cannot all be held at once: each frame builds and
  // consumes them in batches that fit the memory budget (opaque mode only).
  bool batches = false;
};

// The frame (size, background, camera, threads, tiles, budget) and the
// spheres' own: shading, ambient occlusion, mode and visibility.
struct SphereRenderSettings : FrameSettings {
  Shading shading;
  SphereAo ao;
  SphereMode mode = SphereMode::Opaque;
  // Translucent modes: one fragment per sphere and ray (the visible surface)
  // instead of two (entry and exit); the incomplete-image stop once
  // 1 − alpha <= tolerance / 510 (0: never; spheres digest §2.3.7, Eq. 4.2); the layer cap
  // of peel and dual_peel (0: none).
  bool front_surfaces_only = false;
  double tolerance = 8;
  uint32_t max_layers = 32;
  // Visibility (docs/spheres.md): a grid³ cell grid, view-volume culling of
  // its cells, front-to-back occlusion culling of cells against the
  // conservative centre-disc depth map, and the one-level max-depth pyramid
  // test per sphere. Each is lossless: the image is bit-identical without.
  uint32_t grid = 0;  // cells per axis; 0: auto_sphere_grid() of the set's size
  bool culling = true;
};

}  // namespace zs
