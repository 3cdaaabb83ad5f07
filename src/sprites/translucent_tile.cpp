// The translucent tile's shared parts and the exact `sorted` mode
// (translucent_tile.h); the peeling modes are in peel_tile.cpp.
#include "sprites/translucent_tile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "spheres/sphere_shading.h"
#include "sprites/sphere_tile_scan.h"
#include "sprites/sphere_visibility.h"
#include "util/bytes_str.h"

namespace zs {

namespace {
constexpr int kBlock = 8;  // pixels per side of the blocks whose largest cut is kept
}

double TranslucentTile::alpha(uint32_t id) const {
  const float a = (*f_->colors)[id].a;
  return a >= 1.f ? 1.0 : a > 0.f ? double(a) : 0.0;  // NaN: 0 (drawn as nothing)
}

int TranslucentTile::fragments(const SphereHit& h, uint32_t id, bool opaque, FragKey out[2]) const {
  // An opaque sphere's visible surface hides its other one; `front` keeps
  // only the visible surface (the entry, or the exit when the eye is inside).
  if (opaque || f_->rs->front_surfaces_only || h.inside) {
    out[0] = {h.t + 0.0, frag_code(id, h.inside)};  // + 0.0: −0 as +0, as the depth buffer does
    return 1;
  }
  out[0] = {h.t_in + 0.0, frag_code(id, false)};
  out[1] = {h.t_out + 0.0, frag_code(id, true)};
  return 2;
}

void TranslucentTile::color(size_t p, const FragKey& k, double c[4]) const {
  const View& view = *f_->view;
  const CameraPlane& cam = f_->cam;
  const uint32_t id = frag_id(k.code);
  const double X = double(r_.x0 + p % w_), Y = double(r_.y0 + p / w_);
  const glm::dvec3 cc = to_camera(view, f_->s->centres[id]);
  const double R = f_->s->radii[id], t = k.z;
  // As the opaque renderer's resolve: the surface point on the pixel's ray,
  // its normal facing the viewer (an exit surface faces it reversed).
  const double a = (X - cam.ox) / cam.sx, b = (cam.oy - Y) / cam.sy;
  const glm::dvec3 P = view.perspective() ? glm::dvec3(a * t, b * t, t) : glm::dvec3(a, b, t);
  glm::dvec3 n = (P - cc) / R;
  if (frag_exit(k.code)) n = -n;
  n = glm::normalize(glm::dvec3(n.x, n.y, -n.z));
  const glm::dvec3 v = view.perspective() ? glm::normalize(glm::dvec3(-P.x, -P.y, P.z)) : glm::dvec3(0, 0, 1);
  const glm::vec4& col = (*f_->colors)[id];
  const glm::dvec3 rgb = shade(f_->rs->shading, glm::dvec3(col.r, col.g, col.b), n, v);
  const double al = alpha(id);
  c[0] = rgb.r * al, c[1] = rgb.g * al, c[2] = rgb.b * al, c[3] = al;
}

bool TranslucentTile::block_hidden(int i0, int i1, int j0, int j1, double z) {
  const uint32_t bw = (w_ + kBlock - 1) / kBlock;
  for (int by = j0 / kBlock; by <= j1 / kBlock; ++by)
    for (int bx = i0 / kBlock; bx <= i1 / kBlock; ++bx) {
      const size_t b = size_t(by) * bw + size_t(bx);
      if (bdirty_[b]) {
        double m = -INFINITY;
        const uint32_t y1 = std::min<uint32_t>(h_, uint32_t(by + 1) * kBlock);
        const uint32_t x1 = std::min<uint32_t>(w_, uint32_t(bx + 1) * kBlock);
        for (uint32_t y = uint32_t(by) * kBlock; y < y1; ++y)
          for (uint32_t x = uint32_t(bx) * kBlock; x < x1; ++x) m = std::max(m, cut_[size_t(y) * w_ + x]);
        bcut_[b] = m;
        bdirty_[b] = 0;
      }
      if (!(bcut_[b] < z)) return false;
    }
  return true;
}

void TranslucentTile::mark_block(size_t p) {
  const uint32_t bw = (w_ + kBlock - 1) / kBlock;
  bdirty_[size_t(p / w_ / kBlock) * bw + (p % w_) / kBlock] = 1;
}

const float* TranslucentTile::render(const TranslucentFrame& f, const uint32_t* bin, uint64_t count,
                                     const TileRect& r, SphereStats& stats) {
  f_ = &f, bin_ = bin, count_ = count, r_ = r, S_ = &stats;
  w_ = r.width(), h_ = r.height();
  vp_ = {int(r.x0), int(r.y0), int(r.x1), int(r.y1)};
  stop_ = stop_threshold(f.rs->tolerance);
  const size_t n = size_t(w_) * h_;
  acc_.assign(n * 4, 0.0);
  zfirst_.assign(n, INFINITY);
  cut_.assign(n, INFINITY);
  const size_t nb = size_t((w_ + kBlock - 1) / kBlock) * ((h_ + kBlock - 1) / kBlock);
  bcut_.assign(nb, INFINITY);
  bdirty_.assign(nb, 0);
  switch (f.rs->mode) {
    case SphereMode::Sorted: sorted(); break;
    case SphereMode::Peel: peel(); break;
    case SphereMode::DualPeel: dual_peel(); break;
    case SphereMode::Weighted: weighted(); break;
    case SphereMode::Opaque: throw std::logic_error("TranslucentTile: opaque mode");
  }
  finish();
  return out_.data();
}

// ---- sorted ----

void TranslucentTile::sorted() {
  const SphereGrid& g = *f_->g;
  const size_t n = size_t(w_) * h_;
  head_.assign(n, -1);
  pool_.clear();
  active_.clear();
  // Flush when a few fragments per pixel are pending: often enough that
  // finished pixels stop early, rarely enough that a flush's sort is cheap.
  pool_cap_ = std::max<uint64_t>(1024, 4 * n);
  uint64_t peak = 0;
  for (uint64_t q = 0; q < count_; ++q) {
    const uint32_t e = bin_[q], id = g.ids[e];
    const double al = alpha(id);
    if (al == 0) continue;  // (the renderer bins none)
    const bool opaque = al == 1;
    const glm::dvec3 c = to_camera(*f_->view, g.centre[e]);
    const double zmin = c.z - g.radius[e];
    const double z_reject = zmin - 1e-9 * std::abs(zmin);  // no computed depth of the sphere is nearer
    if (pool_.size() >= pool_cap_) {
      flush(z_reject);
      peak = std::max<uint64_t>(peak, pool_.size());
      if (pool_.size() > pool_cap_ / 2) {
        pool_cap_ *= 2;  // little was in front of the plane: flush less often
        if (pool_cap_ > f_->pool_limit && pool_.size() >= f_->pool_limit)
          throw std::runtime_error("the memory budget cannot hold the pending fragments of a " +
                                   std::to_string(w_) + "x" + std::to_string(h_) + " tile (" +
                                   bytes_str(pool_.size() * kFragBytes) +
                                   "); use a larger --memory-budget or a smaller --tile-size");
      }
    }
    const SphereSetup su = setup_sphere(f_->cam, c.x, c.y, c.z, g.radius[e]);
    int i0, i1, j0, j1;
    if (!sphere_pixel_range(su, vp_, &i0, &i1, &j0, &j1)) continue;
    i0 -= vp_.x0, i1 -= vp_.x0, j0 -= vp_.y0, j1 -= vp_.y0;
    if (block_hidden(i0, i1, j0, j1, z_reject)) {
      ++S_->spheres_block_rejected;
      continue;
    }
    ++S_->spheres_scanned;
    for_each_sphere_hit(
        su, vp_, i0, i1, j0, j1, spans_, *S_, [&](size_t p) { return cut_[p] < z_reject; },
        [&](size_t p, const SphereHit& h) {
          FragKey k[2];
          const int m = fragments(h, id, opaque, k);
          for (int u = 0; u < m; ++u) {
            if (k[u].z > cut_[p]) continue;  // behind an opaque fragment already pending
            if (head_[p] < 0) active_.push_back(uint32_t(p));
            pool_.push_back({k[u].z, k[u].code, head_[p]});
            head_[p] = int32_t(pool_.size() - 1);
          }
          if (opaque && k[0].z < cut_[p]) {
            cut_[p] = k[0].z;
            mark_block(p);
          }
        });
    peak = std::max<uint64_t>(peak, pool_.size());
  }
  flush(INFINITY);
  S_->pending_peak = std::max(S_->pending_peak, peak);
}

// Composites, per pixel, the pending fragments in front of z_plane in
// order; keeps the rest.
void TranslucentTile::flush(double z_plane) {
  ++S_->flushes;
  pool2_.clear();
  active2_.clear();
  for (const uint32_t p : active_) {
    scratch_.clear();
    for (int32_t i = head_[p]; i >= 0; i = pool_[size_t(i)].next) scratch_.push_back({pool_[size_t(i)].z, pool_[size_t(i)].code});
    head_[p] = -1;
    if (cut_[p] == -INFINITY) continue;  // done
    std::sort(scratch_.begin(), scratch_.end());
    double* a = &acc_[size_t(p) * 4];
    size_t k = 0;
    bool done = false;
    for (; k < scratch_.size() && scratch_[k].z < z_plane; ++k) {
      const FragKey& fk = scratch_[k];
      double c[4];
      color(p, fk, c);
      if (zfirst_[p] == INFINITY) zfirst_[p] = fk.z;
      composite_under(a, c);
      ++S_->composited;
      if (c[3] == 1.0) {
        done = true;
        break;
      }
      if (saturated(a, stop_)) {
        ++S_->pixels_stopped;
        done = true;
        break;
      }
    }
    if (done) {
      cut_[p] = -INFINITY;
      mark_block(p);
      continue;
    }
    for (; k < scratch_.size(); ++k) {
      if (scratch_[k].z > cut_[p]) break;  // sorted: the rest is behind the opaque fragment too
      pool2_.push_back({scratch_[k].z, scratch_[k].code, head_[p]});
      head_[p] = int32_t(pool2_.size() - 1);
    }
    if (head_[p] >= 0) active2_.push_back(p);
  }
  pool_.swap(pool2_);
  active_.swap(active2_);
}

// The composite over the image background; RGBA + Z out.
void TranslucentTile::finish() {
  const size_t n = size_t(w_) * h_;
  out_.resize(n * 5);
  const double* bg = f_->rs->background;
  for (size_t p = 0; p < n; ++p) {
    float* o = &out_[p * 5];
    double* a = &acc_[p * 4];
    if (f_->rs->mode != SphereMode::Weighted) composite_under(a, bg);
    for (int k = 0; k < 4; ++k) o[k] = float(a[k]);
    o[4] = float(zfirst_[p]);
    if (zfirst_[p] != INFINITY) ++S_->rendered_pixels;
  }
}

}  // namespace zs
