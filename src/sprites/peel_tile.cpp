// The seed's approximate translucency modes on one tile (digest §2.3.4–2.3.8):
// front depth peeling, dual depth peeling and Meshkin's weighted sum, each
// over an opaque background drawn once (translucent_tile.h).
#include <algorithm>
#include <cmath>

#include "sprites/sphere_tile_scan.h"
#include "sprites/sphere_visibility.h"
#include "sprites/translucent_tile.h"

namespace zs {

// The opaque spheres once: per pixel the nearest visible surface of an
// opaque sphere (bg_, and its depth in cut_: translucent fragments behind it
// are hidden), then the list of translucent spheres not wholly behind it.
void TranslucentTile::opaque_background() {
  const SphereGrid& g = *f_->g;
  const size_t n = size_t(w_) * h_;
  bg_.assign(n, kKeyMax);
  live_.clear();
  for (int pass = 0; pass < 2; ++pass)  // opaque spheres, then the translucent ones against them
    for (uint64_t q = 0; q < count_; ++q) {
      const uint32_t e = bin_[q], id = g.ids[e];
      const double al = alpha(id);
      if (al == 0) continue;  // (the renderer bins none)
      const bool opaque = al == 1;
      if (opaque != (pass == 0)) continue;
      const glm::dvec3 c = to_camera(*f_->view, g.centre[e]);
      const double zmin = c.z - g.radius[e];
      const double z_reject = zmin - 1e-9 * std::abs(zmin);
      const SphereSetup su = setup_sphere(f_->cam, c.x, c.y, c.z, g.radius[e]);
      int i0, i1, j0, j1;
      if (!sphere_pixel_range(su, vp_, &i0, &i1, &j0, &j1)) continue;
      i0 -= vp_.x0, i1 -= vp_.x0, j0 -= vp_.y0, j1 -= vp_.y0;
      if (block_hidden(i0, i1, j0, j1, z_reject)) {
        ++S_->spheres_block_rejected;
        continue;
      }
      if (!opaque) {
        live_.push_back({su, i0, i1, j0, j1, z_reject, id});
        continue;
      }
      ++S_->spheres_scanned;
      for_each_sphere_hit(
          su, vp_, i0, i1, j0, j1, spans_, *S_, [&](size_t p) { return cut_[p] < z_reject; },
          [&](size_t p, const SphereHit& h) {
            FragKey k[2];
            fragments(h, id, true, k);
            if (k[0] < bg_[p]) {
              bg_[p] = k[0];
              cut_[p] = k[0].z;
              mark_block(p);
            }
          });
    }
}

// One pass over the live translucent spheres: fn(p, key) for each of their
// fragments at pixels not done. Spheres for which live(sphere) stays false
// are dropped from the list for good (the seed's cached survivor list).
template <class Fn>
static void peel_pass(std::vector<TranslucentTile::Live>& live, const Viewport& vp, FaceSpans& spans, SphereStats& S,
                      const std::vector<double>& cut, bool front_only, Fn&& fn) {
  size_t keep = 0;
  ++S.passes;
  for (size_t q = 0; q < live.size(); ++q) {
    const TranslucentTile::Live& L = live[q];
    bool any = false;
    ++S.spheres_scanned;
    for_each_sphere_hit(
        L.su, vp, L.i0, L.i1, L.j0, L.j1, spans, S, [&](size_t p) { return cut[p] < L.z_reject; },
        [&](size_t p, const SphereHit& h) {
          if (front_only || h.inside) {
            any |= fn(p, FragKey{h.t + 0.0, frag_code(L.id, h.inside)});
          } else {
            any |= fn(p, FragKey{h.t_in + 0.0, frag_code(L.id, false)});
            any |= fn(p, FragKey{h.t_out + 0.0, frag_code(L.id, true)});
          }
        });
    if (any) live[keep++] = L;
  }
  live.resize(keep);
}

void TranslucentTile::peel() {
  const size_t n = size_t(w_) * h_;
  opaque_background();
  prev_.assign(n, kKeyMin);
  layers_.assign(n, 0);
  const uint32_t cap = f_->rs->max_layers;
  const bool front = f_->rs->front_surfaces_only;
  for (uint32_t layer = 0; (cap == 0 || layer < cap) && !live_.empty(); ++layer) {
    cur_.assign(n, kKeyMax);
    // The nearest fragment behind the last layer and in front of the
    // background; a sphere with none anywhere can give no later layer.
    peel_pass(live_, vp_, spans_, *S_, cut_, front, [&](size_t p, const FragKey& k) {
      if (!(prev_[p] < k && k < bg_[p])) return false;
      if (k < cur_[p]) cur_[p] = k;
      return true;
    });
    bool any = false;
    for (size_t p = 0; p < n; ++p) {
      if (cur_[p].z == INFINITY) continue;
      any = true;
      double c[4];
      color(p, cur_[p], c);
      if (zfirst_[p] == INFINITY) zfirst_[p] = cur_[p].z;
      double* a = &acc_[p * 4];
      composite_under(a, c);
      ++S_->composited;
      ++layers_[p];
      prev_[p] = cur_[p];
      if (saturated(a, stop_)) {  // Eq. 4.2: this pixel takes no more layers
        ++S_->pixels_stopped;
        cut_[p] = -INFINITY;
        mark_block(p);
      }
    }
    if (!any) break;
  }
  // The background under what was peeled (also where the cap left layers out).
  for (size_t p = 0; p < n; ++p) {
    if (bg_[p].z == INFINITY || cut_[p] == -INFINITY) continue;
    double c[4];
    color(p, bg_[p], c);
    if (zfirst_[p] == INFINITY) zfirst_[p] = bg_[p].z;
    composite_under(&acc_[p * 4], c);
    ++S_->composited;
  }
  for (size_t p = 0; p < n; ++p) {
    S_->layers_max = std::max<uint64_t>(S_->layers_max, layers_[p]);
    S_->layer_sum += layers_[p];
    S_->layer_pixels += layers_[p] > 0;
  }
}

void TranslucentTile::dual_peel() {
  const size_t n = size_t(w_) * h_;
  opaque_background();
  prev_.assign(n, kKeyMin);  // the front layers peeled so far end here
  far_ = bg_;                // the back layers (and the background) begin here
  back_.assign(n * 4, 0.0);
  layers_.assign(n, 0);
  for (size_t p = 0; p < n; ++p)
    if (bg_[p].z != INFINITY) color(p, bg_[p], &back_[p * 4]);
  const uint32_t cap = f_->rs->max_layers, passes = cap ? (cap + 1) / 2 : 0;
  const bool front = f_->rs->front_surfaces_only;
  for (uint32_t pass = 0; (passes == 0 || pass < passes) && !live_.empty(); ++pass) {
    cur_.assign(n, kKeyMax);
    mx_.assign(n, kKeyMin);
    peel_pass(live_, vp_, spans_, *S_, cut_, front, [&](size_t p, const FragKey& k) {
      if (!(prev_[p] < k && k < far_[p])) return false;
      if (k < cur_[p]) cur_[p] = k;
      if (mx_[p] < k) mx_[p] = k;
      return true;
    });
    bool any = false;
    for (size_t p = 0; p < n; ++p) {
      if (cur_[p].z == INFINITY) continue;
      any = true;
      double c[4];
      color(p, cur_[p], c);
      if (zfirst_[p] == INFINITY) zfirst_[p] = cur_[p].z;
      composite_under(&acc_[p * 4], c);
      ++S_->composited;
      ++layers_[p];
      prev_[p] = cur_[p];
      if (!(mx_[p] == cur_[p])) {  // the farthest left, over the back layers
        color(p, mx_[p], c);
        composite_over(&back_[p * 4], c);
        ++S_->composited;
        ++layers_[p];
        far_[p] = mx_[p];
      }
    }
    if (!any) break;
  }
  for (size_t p = 0; p < n; ++p) {
    if (zfirst_[p] == INFINITY && bg_[p].z != INFINITY) zfirst_[p] = bg_[p].z;
    composite_under(&acc_[p * 4], &back_[p * 4]);  // front layers over back layers (and the background)
    S_->layers_max = std::max<uint64_t>(S_->layers_max, layers_[p]);
    S_->layer_sum += layers_[p];
    S_->layer_pixels += layers_[p] > 0;
  }
}

void TranslucentTile::weighted() {
  const size_t n = size_t(w_) * h_;
  opaque_background();
  const bool front = f_->rs->front_surfaces_only;
  // One pass: X = Σ premultiplied colours of the fragments in front of the
  // opaque background, in any order (sums of a pixel's fragments are added
  // in the tile's fixed sphere order, so the image is still deterministic).
  peel_pass(live_, vp_, spans_, *S_, cut_, front, [&](size_t p, const FragKey& k) {
    if (!(k < bg_[p])) return false;
    double c[4];
    color(p, k, c);
    double* x = &acc_[p * 4];
    for (int i = 0; i < 4; ++i) x[i] += c[i];
    zfirst_[p] = std::min(zfirst_[p], k.z);
    ++S_->composited;
    return true;
  });
  const double* image_bg = f_->rs->background;
  for (size_t p = 0; p < n; ++p) {
    double w[4], out[4];
    if (bg_[p].z != INFINITY) {
      color(p, bg_[p], w);
      zfirst_[p] = std::min(zfirst_[p], bg_[p].z);
    } else {
      std::copy(image_bg, image_bg + 4, w);
    }
    weighted_sum(&acc_[p * 4], w, out);
    std::copy(out, out + 4, &acc_[p * 4]);
  }
}

}  // namespace zs
