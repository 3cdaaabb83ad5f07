// The seed's approximate translucency modes on one tile (spheres digest §2.3.4–2.3.8):
// front depth peeling, dual depth peeling and Meshkin's weighted sum, each
// over an opaque background drawn once (translucent_tile.h).
#include <algorithm>
#include <cmath>

#include "render/spheres/translucent_tile.h"

namespace zs {

// The opaque spheres once: per pixel the nearest visible surface of an
// opaque sphere (bg_; its depth bounds the pixel: translucent fragments
// behind it are hidden), then the translucent spheres as the live list.
void TranslucentTile::opaque_background() {
  const size_t n = size_t(w_) * h_;
  bg_.assign(n, kKeyMax);
  gather_live(Which::Opaque);
  begin_pass();
  --S_->passes;  // not a peeling pass
  pass([&](size_t p, const FragKey& k, bool) {
    if (k < bg_[p]) {
      bg_[p] = k;
      set_gone(p, k.z);
    }
    return false;
  });
  gather_live(Which::Translucent);
}

double* TranslucentTile::composite_layer(size_t p, const FragKey& k) {
  double c[4];
  color(p, k, c);
  note_first(p, k);
  double* a = &acc_[p * 4];
  composite_under(a, c);
  ++S_->composited;
  ++layers_[p];
  prev_[p] = k;
  return a;
}

void TranslucentTile::peel() {
  const size_t n = size_t(w_) * h_;
  opaque_background();
  layers_.assign(n, 0);
  const uint32_t cap = f_->rs->max_layers;
  for (uint32_t layer = 0; (cap == 0 || layer < cap) && !live_.empty(); ++layer) {
    begin_pass();
    cur_.assign(n, kKeyMax);
    // The nearest fragment behind the last layer and in front of the
    // background; a sphere with none anywhere gives no later layer.
    pass([&](size_t p, const FragKey& k, bool) {
      if (!(prev_[p] < k && k < bg_[p])) return false;
      if (k < cur_[p]) {
        cur_[p] = k;
        set_now(p, k.z);
      }
      return true;
    });
    bool any = false;
    for (size_t p = 0; p < n; ++p) {
      if (cur_[p].z == INFINITY) continue;
      any = true;
      const double* a = composite_layer(p, cur_[p]);
      if (opaque_now(a)) {
        set_gone(p, -INFINITY);  // exact: nothing behind can change it
      } else if (saturated(a, stop_)) {  // Eq. 4.2: this pixel takes no more layers
        ++S_->pixels_stopped;
        set_gone(p, -INFINITY);
      }
    }
    if (!any) break;
  }
  // The background under what was peeled (also where the cap left layers out).
  for (size_t p = 0; p < n; ++p) {
    if (bg_[p].z == INFINITY || gone_[p] == -INFINITY) continue;
    double c[4];
    color(p, bg_[p], c);
    note_first(p, bg_[p]);
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
  far_ = bg_;  // the back layers (and the background) begin here; prev_: the front ones end
  back_.assign(n * 4, 0.0);
  layers_.assign(n, 0);
  for (size_t p = 0; p < n; ++p)
    if (bg_[p].z != INFINITY) color(p, bg_[p], &back_[p * 4]);
  const uint32_t cap = f_->rs->max_layers, passes = cap ? (cap + 1) / 2 : 0;
  for (uint32_t pass_no = 0; (passes == 0 || pass_no < passes) && !live_.empty(); ++pass_no) {
    begin_pass();
    cur_.assign(n, kKeyMax);
    mx_.assign(n, kKeyMin);
    pass([&](size_t p, const FragKey& k, bool) {
      if (!(prev_[p] < k && k < far_[p])) return false;
      if (k < cur_[p]) cur_[p] = k;
      if (mx_[p] < k) mx_[p] = k;
      return true;
    });
    bool any = false;
    for (size_t p = 0; p < n; ++p) {
      if (cur_[p].z == INFINITY) continue;
      any = true;
      composite_layer(p, cur_[p]);
      if (!(mx_[p] == cur_[p])) {  // the farthest left goes over the back layers
        double c[4];
        color(p, mx_[p], c);
        composite_over(&back_[p * 4], c);
        ++S_->composited;
        ++layers_[p];
        far_[p] = mx_[p];
        set_gone(p, mx_[p].z);  // nothing behind it is peeled any more
      }
    }
    if (!any) break;
  }
  for (size_t p = 0; p < n; ++p) {
    if (bg_[p].z != INFINITY) note_first(p, bg_[p]);
    composite_under(&acc_[p * 4], &back_[p * 4]);  // front layers over back layers (and the background)
    S_->layers_max = std::max<uint64_t>(S_->layers_max, layers_[p]);
    S_->layer_sum += layers_[p];
    S_->layer_pixels += layers_[p] > 0;
  }
}

void TranslucentTile::weighted() {
  const size_t n = size_t(w_) * h_;
  opaque_background();
  begin_pass();
  // One pass: X = Σ premultiplied colours of the fragments in front of the
  // opaque background, in the tile's sphere order (the same in every tile:
  // the bins keep one global order).
  pass([&](size_t p, const FragKey& k, bool) {
    if (!(k < bg_[p])) return false;
    double c[4];
    color(p, k, c);
    double* x = &acc_[p * 4];
    for (int i = 0; i < 4; ++i) x[i] += c[i];
    note_first(p, k);
    ++S_->composited;
    return true;
  });
  const double* image_bg = f_->rs->background;
  for (size_t p = 0; p < n; ++p) {
    double w[4], out[4];
    if (bg_[p].z != INFINITY) {
      color(p, bg_[p], w);
      note_first(p, bg_[p]);
    } else {
      std::copy(image_bg, image_bg + 4, w);
    }
    weighted_sum(&acc_[p * 4], w, out);
    std::copy(out, out + 4, &acc_[p * 4]);
  }
}

}  // namespace zs
