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

#include <vector>

#include "lighting/light.h"
#include "lighting/shadow_map.h"
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

// A directional light's map lookup as functions of the pixel's camera-plane
// coordinates (a, b) and view depth s, so a pixel needs no world point: with
// p = E + s·w, w = F + a·R + b·U (perspective) or p = E + a·R + b·U + s·F,
// an affine Q(p) (ShadowMap::affine_lookup) is QE + s·(QF + a·QR + b·QU) or
// QE + a·QR + b·QU + s·QF. The bias's normal part is per triangle (its
// face normal g).
struct MapLookup {
  double e[3], f[3], r[3], u[3];  // QE, QF, QR, QU for Q = map column X, row Y, light depth z
  std::vector<double> face_bias;  // per TriangleShade; NaN: turned from the light
};
MapLookup map_lookup(const View& view, const ShadowMap& map, const Light& light,
                     const std::vector<TriangleShade>& shades);

// The least and greatest depth of the batch's covered pixels (+inf, −inf
// when none is covered; NaN if a depth is).
void depth_range(const ShadeBatch& b, double* lo, double* hi);

// Bounds on map_inputs' X, Y and light depth z over pixels with a between
// a0 and a1 and depth s in [s0, s1]: each is bilinear (perspective) or affine
// (orthographic) in (a, s), so its extremes are at the four corners. Out:
// x[0..1], y[0..1], z[0..1] (low, high), before any rounding margin.
void map_range(const MapLookup& M, bool perspective, double a0, double a1, double cb, double s0, double s1, double* x,
               double* y, double* z);

// The map column X, row Y and test limit lim = z − bias_total (shadow_map.h)
// of n pixels, for ShadowMap::counts_at.
void map_inputs(const MapLookup& M, bool perspective, int n, const double* __restrict ca, double cb,
                const double* __restrict depth, const uint32_t* __restrict tri,
                double* __restrict X, double* __restrict Y, double* __restrict lim);

}  // namespace zs
