// Shading the covered pixels of a tile row together, as arrays: the hit
// and normals from each pixel's triangle set-up (triangle_shade.h: one
// division per pixel, no intersection), Blinn–Phong per light
// (surface_shading.h), laid out so that the compiler vectorizes it and
// independent pixels overlap their square roots and divisions. The shadow
// tests run between the two steps, per light.
#pragma once

#include <cstdint>

#include "shadows/light.h"
#include "surface/surface_shading.h"
#include "surface/triangle_shade.h"
#include "view/camera.h"

namespace zs {

constexpr int kShadeBatch = 64;

struct ShadeBatch {
  int n = 0;
  // In: pixel column (row Y is the batch's), the triangle's set-up (index
  // into the frame's TriangleShade array), rasterized depth, and the pixel's
  // index in the tile.
  double X[kShadeBatch], zbuf[kShadeBatch];
  uint32_t tri[kShadeBatch], pixel[kShadeBatch];
  // Out of surface_hits: the hit point, the geometric and shading normals
  // (unit, facing the eye), the unit vector to the eye and the view depth.
  double px[kShadeBatch], py[kShadeBatch], pz[kShadeBatch];
  double gx[kShadeBatch], gy[kShadeBatch], gz[kShadeBatch];
  double sx[kShadeBatch], sy[kShadeBatch], sz[kShadeBatch];
  double vx[kShadeBatch], vy[kShadeBatch], vz[kShadeBatch];
  double depth[kShadeBatch];
  float base[3][kShadeBatch];  // the surface's colour
  // Accumulated by add_lights.
  double diffuse[kShadeBatch], specular[kShadeBatch];
};

// Hit points and normals of the batch's pixels on row Y; zeroes the sums.
void surface_hits(const View& view, double Y, const TriangleShade* shades, ShadeBatch& b);

// Adds one light's diffuse and specular terms, scaled by each pixel's lit
// fraction (add_light of surface_shading.h, pixel by pixel).
void add_lights(const SurfaceShading& sh, const Light& light, const double* lit, ShadeBatch& b);

// The pixels' colours, base·(ambient + diffuse) + specular clamped to
// [0, 1] (surface_shading.h's surface_colour), per channel.
void surface_colours(const ShadeBatch& b, double ambient, float rgb[3][kShadeBatch]);

}  // namespace zs
