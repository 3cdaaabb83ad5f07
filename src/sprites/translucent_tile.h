// One tile of a translucent sphere render (digest §2.3; docs/spheres.md,
// "Translucency"). A translucent sphere is a shell: each ray crossing it
// gives two fragments (entry and exit; with `surfaces: front` only the
// visible one), composited front to back with the sphere's colour, shaded at
// that surface, and alpha. A sphere of alpha 1 is opaque: its visible
// surface ends the pixel. Alpha 0 draws nothing.
//
// - sorted: exact. The tile's spheres arrive nearest first (by the nearest
//   depth they can have), so once the next one's nearest depth is Z every
//   fragment in front of Z is known: pending fragments in front of Z are
//   sorted per pixel and composited (the ZSweep engine's delayed
//   compositing, with the sweep plane at Z), whenever the pending pool
//   fills. A pixel stops once opaque or, with a tolerance t, once
//   1 − A <= t/510 (Eq. 4.2); its later fragments are never made.
// - peel: the seed's front depth peeling: the opaque spheres once into a
//   background (depth and colour), then one pass over the translucent
//   spheres per layer, each keeping per pixel the nearest fragment behind the
//   last layer and in front of the background; the same stop, a layer cap,
//   and the list of spheres that may still give a layer, shrunk every pass
//   (the seed's transform-feedback cache). Run to completion it is `sorted`
//   bit for bit.
// - dual_peel: two layers per pass (nearest and farthest left), the back
//   ones composited back to front; no early stop.
// - weighted: Meshkin's order-independent weighted sum over the background.
//
// Every result is a function of the pixel's set of fragments and their total
// order (FragKey), so tiles, threads and culling never change a bit.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/raster_target.h"
#include "raster/sphere_span.h"
#include "raster/tile_grid.h"
#include "spheres/sphere_set.h"
#include "sprites/fragment_composite.h"
#include "sprites/sphere_grid.h"
#include "sprites/sphere_settings.h"
#include "sprites/sphere_stats.h"
#include "view/camera.h"

namespace zs {

// What every tile of a frame shares.
struct TranslucentFrame {
  const SphereSet* s;
  const SphereGrid* g;
  const std::vector<glm::vec4>* colors;
  const SphereRenderSettings* rs;
  const View* view;
  CameraPlane cam;
  uint64_t pool_limit;  // pending fragments a thread may hold (sorted), from the memory budget
};

// A thread's scratch, reused from tile to tile (no allocation per fragment).
class TranslucentTile {
 public:
  // Renders the tile from its bin (grid entries, nearest first) into RGBA +
  // Z floats per pixel; adds its counts to `stats`. Throws
  // std::runtime_error when sorted's pending fragments outgrow pool_limit.
  const float* render(const TranslucentFrame& f, const uint32_t* bin, uint64_t count, const TileRect& r,
                      SphereStats& stats);

  // Bytes per pending fragment (sorted), for budgets.
  static constexpr uint64_t kFragBytes = 24;

  struct Live {  // a translucent sphere that may still give a layer
    SphereSetup su;
    int i0, i1, j0, j1;  // pixel range, tile coordinates
    double z_reject;     // no computed depth of it is nearer
    uint32_t id;
  };

 private:
  struct Frag {
    double z;
    uint64_t code;
    int32_t next;  // the pixel's next pending fragment, -1: none
  };

  void sorted();
  void flush(double z_plane);
  void peel();
  void dual_peel();
  void weighted();
  void opaque_background();
  void finish();  // acc over the image background, Z, into out_

  // The fragment's premultiplied colour (shaded as the opaque renderer shades).
  void color(size_t p, const FragKey& k, double c[4]) const;
  double alpha(uint32_t id) const;
  // Pixel p's fragments of the sphere hit by `h` (one or two), in order.
  int fragments(const SphereHit& h, uint32_t id, bool opaque, FragKey out[2]) const;
  bool block_hidden(int i0, int i1, int j0, int j1, double z);
  void mark_block(size_t p);

  const TranslucentFrame* f_ = nullptr;
  const uint32_t* bin_ = nullptr;
  uint64_t count_ = 0;
  TileRect r_{};
  Viewport vp_{};
  uint32_t w_ = 0, h_ = 0;
  SphereStats* S_ = nullptr;
  double stop_ = -1;

  std::vector<double> acc_;    // 4 per pixel: the composite so far, premultiplied
  std::vector<double> zfirst_; // the nearest fragment composited (Z)
  std::vector<double> cut_;    // fragments behind this cannot count (an opaque one in front; -inf: pixel done)
  std::vector<double> bcut_;   // per 8×8 block: the largest cut (lazily)
  std::vector<uint8_t> bdirty_;
  // sorted
  std::vector<Frag> pool_, pool2_;
  std::vector<int32_t> head_;
  std::vector<uint32_t> active_, active2_;
  std::vector<FragKey> scratch_;
  uint64_t pool_cap_ = 0;
  // peeling
  std::vector<FragKey> bg_, prev_, cur_, far_, mx_;
  std::vector<double> back_;  // dual peeling's back composite, 4 per pixel
  std::vector<Live> live_;
  std::vector<uint32_t> layers_;
  FaceSpans spans_;
  std::vector<float> out_;
};

}  // namespace zs
