// What every renderer shares (docs/renderers.md): the image's size and
// background, the camera, the threads, the tile size and the memory budget.
// Each renderer's settings (RenderSettings, SphereRenderSettings,
// SurfaceRenderSettings, and the reference's) are a FrameSettings plus their
// own knobs.
#pragma once

#include <cstdint>

#include "base/util/memory.h"
#include "base/view/camera.h"
#include "base/view/clip_region.h"

namespace zs {

struct FrameSettings {
  uint32_t width = 512, height = 512;
  double background[4] = {0, 0, 0, 0};  // premultiplied RGBA, where nothing is drawn
  Camera camera;
  // The scene's clip planes and crop box (empty: keep everything); the
  // volume renderers cut their segments to it.
  ClipRegion clip;
  int threads = 1;
  // Screen tiles are rendered independently (raster/tile_loop.h); the image
  // does not depend on their size, only speed and memory do.
  uint32_t tile_size = 64;
  // What a frame may hold at once; 0 means the default below.
  uint64_t memory_budget_bytes = 0;
  bool progress = false;  // progress bar on stderr

  uint64_t budget() const;
};

// The budget's one default rule: the budget asked for, else (0) half of this
// machine's physical memory (base/util/memory.h).
inline uint64_t frame_budget(uint64_t asked) { return asked ? asked : default_memory_budget(); }
inline uint64_t FrameSettings::budget() const { return frame_budget(memory_budget_bytes); }

}  // namespace zs
