// One tile of a translucent sphere render (spheres digest §2.3; docs/spheres.md,
// "Translucency"). A translucent sphere is a shell: each ray crossing it
// gives two fragments (entry and exit; with `surfaces: front` only the
// visible one), composited front to back with the sphere's colour, shaded at
// that surface, and alpha. A sphere of alpha 1 is opaque: its visible
// surface ends the pixel. Alpha 0 draws nothing.
//
// - sorted: exact. Passes over the tile's spheres, each keeping per open
//   pixel at most K nearest fragments behind those composited so far (a
//   k-buffer that drops its far half when full), then compositing them in
//   order; a pixel leaves the passes once opaque, once 1 − A <= t/510 with
//   tolerance t (Eq. 4.2), or once none was dropped. K starts at
//   kSortedLayers (most pixels of a shallow set end in that pass) and grows
//   64-fold per pass within the thread's share of the memory budget, so a
//   pixel thousands of fragments deep takes three passes, not hundreds.
// - peel: the seed's front depth peeling: the opaque spheres once into a
//   background (depth and colour), then one pass over the translucent
//   spheres per layer, each keeping per pixel the nearest fragment behind the
//   last layer and in front of the background; the same stop, a layer cap,
//   and the list of spheres that may still give a layer, shrunk every pass
//   (the seed's transform-feedback cache). Run to completion it is `sorted`
//   bit for bit (a one-fragment k-buffer).
// - dual_peel: two layers per pass (nearest and farthest left), the back
//   ones composited back to front; no early stop.
// - weighted: Meshkin's order-independent weighted sum over the background.
//
// Every pass skips, per 8×8 block and per pixel, spheres whose depth bound
// lies behind the pixel's thresholds (sphere_tile_scan.h). Every result is a
// function of the pixel's set of fragments and their total order (FragKey),
// so tiles, threads and culling never change a bit.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/raster_target.h"
#include "raster/sphere_span.h"
#include "raster/tile_grid.h"
#include "lighting/sphere_map.h"
#include "geometry/spheres/sphere_set.h"
#include "render/spheres/fragment_composite.h"
#include "render/spheres/sphere_grid.h"
#include "render/spheres/sphere_settings.h"
#include "render/spheres/sphere_stats.h"
#include "render/spheres/sphere_tile_scan.h"
#include "base/view/camera.h"

namespace zs {

// What every tile of a frame shares.
struct TranslucentFrame {
  const SphereSet* s;
  const SphereGrid* g;
  const std::vector<glm::vec4>* colors;
  const SphereRenderSettings* rs;
  const View* view;
  CameraPlane cam;
  uint64_t kbuf_bytes;  // sorted: the most a thread's k-buffer may hold
  const SphereAoMaps* ao = nullptr;  // ambient occlusion: every fragment's colour × its AO, and an AO channel
};

// A thread's scratch, reused from tile to tile (no allocation per fragment).
class TranslucentTile {
 public:
  // Renders the tile from its bin (grid entries, nearest first) into RGBA +
  // Z floats per pixel (+ AO with f.ao: the AO at the nearest fragment
  // composited); adds its counts to `stats`.
  const float* render(const TranslucentFrame& f, const uint32_t* bin, uint64_t count, const TileRect& r,
                      SphereStats& stats);

  // sorted's k-buffer depth, and a thread's bytes per tile pixel (for budgets).
  static constexpr uint32_t kSortedLayers = 16;
  static constexpr uint64_t kPixelBytes = kSortedLayers * 16 + 160;

  struct Live {  // a sphere that may still give a layer
    SphereSetup su;      // set up when a pass first reaches it
    int i0, i1, j0, j1;  // pixel range, tile coordinates
    double z_reject;     // no computed depth of it is nearer
    uint32_t e, id;      // grid entry, sphere index
    bool opaque, ready;
  };

 private:
  void sorted();
  void peel();
  void dual_peel();
  void weighted();
  void opaque_background();
  enum class Which { All, Opaque, Translucent };
  void gather_live(Which which);
  void finish();  // acc over the image background, Z, into out_
  // One pass over live_: fn(p, key) for the fragments it may need; drops
  // the spheres for which neither fn returned true nor a pixel was skipped
  // for now (they can give nothing in a later pass).
  template <class Fn>
  void pass(Fn&& fn);
  void set_gone(size_t p, double z);
  void set_now(size_t p, double z);
  void begin_pass();  // now = gone everywhere
  bool set_up(Live& L) const;  // false: it covers no pixel centre of the tile
  double now_tile_max();       // the farthest `now` of the tile

  // Composites layer fragment k under pixel p (peeling modes); its composite.
  double* composite_layer(size_t p, const FragKey& k);
  // The fragment's premultiplied colour (shaded as the opaque renderer
  // shades; with AO, × the AO at its point with the sphere's outward normal).
  void color(size_t p, const FragKey& k, double c[4]) const;
  double fragment_ao(size_t p, const FragKey& k) const;
  // Pixel p composited fragment k: the nearest so far gives Z (and AO).
  void note_first(size_t p, const FragKey& k) {
    if (k < kfirst_[p]) kfirst_[p] = k, zfirst_[p] = k.z;
  }
  double alpha(uint32_t id) const;
  // Pixel p's fragments of the sphere hit by `h` (one or two), in order.
  int fragments(const SphereHit& h, uint32_t id, bool opaque, FragKey out[2]) const;

  const TranslucentFrame* f_ = nullptr;
  const uint32_t* bin_ = nullptr;
  uint64_t count_ = 0;
  TileRect r_{};
  Viewport vp_{};
  uint32_t w_ = 0, h_ = 0;
  SphereStats* S_ = nullptr;
  double stop_ = -1;

  std::vector<double> acc_;     // 4 per pixel: the composite so far, premultiplied
  std::vector<double> zfirst_;  // the nearest fragment composited (Z)
  std::vector<FragKey> kfirst_;  // ... and its key
  std::vector<double> gone_;    // fragments behind this can never count (-inf: pixel done)
  std::vector<double> now_;     // ... cannot count in this pass
  BlockMax gone_max_, now_max_;
  std::vector<Live> live_;
  std::vector<double> zsuf_;    // suffix minima of live_'s z_reject
  std::vector<double> zlow_;
  FaceSpans spans_;
  std::vector<FragKey> prev_;   // the last fragment composited
  // sorted
  std::vector<FragKey> kbuf_;   // K per open pixel, unordered
  std::vector<FragKey> kcut_;   // per pixel: this pass keeps only fragments in front of it
  std::vector<uint32_t> kcount_, kslot_;
  // peeling
  std::vector<FragKey> bg_, cur_, far_, mx_;
  std::vector<double> back_;  // dual peeling's back composite, 4 per pixel
  std::vector<uint32_t> layers_;
  std::vector<float> out_;
};

template <class Fn>
void TranslucentTile::pass(Fn&& fn) {
  const PixelThresholds th{gone_.data(), now_.data(), &gone_max_, &now_max_};
  // live_ is in nearest-depth order (the bin's), so once every sphere left
  // lies behind every pixel's `now`, the pass has nothing left to find:
  // the rest is kept, untouched, for later passes. Checked every
  // kBreakEvery spheres against the suffix minima of z_reject.
  constexpr size_t kBreakEvery = 64;
  const size_t n = live_.size();
  zsuf_.resize(n + 1);
  zsuf_[n] = INFINITY;
  for (size_t q = n; q-- > 0;) zsuf_[q] = std::min(zsuf_[q + 1], live_[q].z_reject);
  size_t keep = 0;
  for (size_t q = 0; q < n; ++q) {
    if (q % kBreakEvery == 0 && zsuf_[q] > now_tile_max()) {
      for (; q < n; ++q) live_[keep++] = live_[q];
      break;
    }
    Live& L = live_[q];
    if (!L.ready && !set_up(L)) continue;
    bool useful = false;
    ++S_->spheres_scanned;
    const bool deferred = for_each_sphere_hit(L.su, vp_, L.i0, L.i1, L.j0, L.j1, L.z_reject, th, zlow_, spans_, *S_,
                                              [&](size_t p, const SphereHit& h) {
                                                FragKey k[2];
                                                const int m = fragments(h, L.id, L.opaque, k);
                                                for (int u = 0; u < m; ++u) useful |= fn(p, k[u], L.opaque);
                                              });
    if (useful || deferred) live_[keep++] = L;
  }
  live_.resize(keep);
}

}  // namespace zs
