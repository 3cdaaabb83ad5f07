// Shading a tile row's pixels together, as arrays: the hit and
// normals from each pixel's triangle set-up (triangle_shade.h: one division
// per pixel, no intersection), Blinn–Phong per light (surface_shading.h),
// laid out so that the compiler vectorizes it and independent pixels overlap
// their square roots and divisions. Positions and depths are doubles (the
// shadow tests need them); the unit vectors and the shading are floats (the
// output's precision), twice as many lanes per instruction. The shadow tests
// run between the two steps, per light.
#pragma once

#include <cstdint>

#include "lighting/light.h"
#include "lighting/surface_shading.h"
#include "render/surfaces/triangle_shade.h"
#include "base/view/camera.h"

namespace zs {

constexpr int kShadeBatch = 64;
constexpr uint32_t kNoShade = 0xffffffffu;  // a pixel no triangle covers (the z-buffer's kNoId)

struct ShadeBatch {
  int n = 0;
  bool points = false;  // in: also give the hit points (spot lights, shadow rays)
  // In: consecutive pixels of row Y: their columns, their triangles' set-ups
  // (index into the frame's TriangleShade array; kNoShade where none: the
  // background, which every step passes over or computes and drops) and
  // rasterized depths. `tri` is `id` with 0 for kNoShade, an index that is
  // safe to read through.
  double Y = 0;
  double X[kShadeBatch] = {}, zbuf[kShadeBatch] = {};
  uint32_t id[kShadeBatch] = {}, tri[kShadeBatch] = {};
  // Out of surface_hits: the camera-plane coordinates (triangle_shade.h; b
  // is the row's, cb), the view depth, the hit point (when `points`), the
  // unit shading normal (facing the eye) and the unit vector to the eye.
  double cb = 0;
  double ca[kShadeBatch] = {}, depth[kShadeBatch] = {};
  double px[kShadeBatch] = {}, py[kShadeBatch] = {}, pz[kShadeBatch] = {};
  float sx[kShadeBatch] = {}, sy[kShadeBatch] = {}, sz[kShadeBatch] = {};
  float vx[kShadeBatch] = {}, vy[kShadeBatch] = {}, vz[kShadeBatch] = {};
  float base[3][kShadeBatch] = {};  // the surface's colour
  // Accumulated by add_lights.
  float diffuse[kShadeBatch] = {}, specular[kShadeBatch] = {};
};

// Hit points and normals of the batch's covered pixels; zeroes the sums.
void surface_hits(const View& view, const TriangleShade* shades, ShadeBatch& b);

// Adds one light's diffuse and specular terms, scaled by each pixel's lit
// fraction (add_light of surface_shading.h, pixel by pixel).
void add_lights(const SurfaceShading& sh, const Light& light, const float* lit, ShadeBatch& b);

// The pixels' colours, base·(ambient + diffuse) + specular clamped to
// [0, 1] (surface_shading.h's surface_colour), per channel.
void surface_colours(const ShadeBatch& b, double ambient, float rgb[3][kShadeBatch]);

// The least and greatest depth of the batch's covered pixels (+inf, −inf
// when none is covered; NaN if a depth is).
void depth_range(const ShadeBatch& b, double* lo, double* hi);

}  // namespace zs
