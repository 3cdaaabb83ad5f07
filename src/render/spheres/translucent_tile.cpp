// The translucent tile's shared parts and the exact `sorted` mode
// (translucent_tile.h); the peeling modes are in peel_tile.cpp.
#include "render/spheres/translucent_tile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "lighting/shading_model.h"
#include "render/spheres/sphere_ao.h"
#include "render/spheres/sphere_tile_scan.h"
#include "render/spheres/sphere_visibility.h"

namespace zs {

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
  glm::dvec3 rgb = shade(f_->rs->shading, glm::dvec3(col.r, col.g, col.b), n, v);
  if (f_->ao) rgb *= fragment_ao(p, k);  // colour = AO × shaded colour (spheres digest §2.4.6)
  const double al = alpha(id);
  c[0] = rgb.r * al, c[1] = rgb.g * al, c[2] = rgb.b * al, c[3] = al;
}

double TranslucentTile::fragment_ao(size_t p, const FragKey& k) const {
  const View& view = *f_->view;
  const CameraPlane& cam = f_->cam;
  const uint32_t id = frag_id(k.code);
  const double X = double(r_.x0 + p % w_), Y = double(r_.y0 + p / w_);
  const glm::dvec3 cc = to_camera(view, f_->s->centres[id]);
  const double t = k.z;
  const double a = (X - cam.ox) / cam.sx, b = (cam.oy - Y) / cam.sy;
  const glm::dvec3 P = view.perspective() ? glm::dvec3(a * t, b * t, t) : glm::dvec3(a, b, t);
  // The outward normal, entry or exit (AO is the light reaching the sphere's
  // surface from outside), by the opaque renderer's steps: a front surface
  // gets its AO bit for bit.
  glm::dvec3 n = (P - cc) / f_->s->radii[id];
  n = glm::normalize(glm::dvec3(n.x, n.y, -n.z));
  glm::dvec3 Pw, Nw;
  ao_world(view, P, n, &Pw, &Nw);
  return ambient_occlusion(*f_->ao, Pw, Nw);
}

void TranslucentTile::set_gone(size_t p, double z) {
  if (z < gone_[p]) {
    gone_[p] = z;
    gone_max_.mark(p);
  }
  set_now(p, z);
}

void TranslucentTile::set_now(size_t p, double z) {
  if (z < now_[p]) {
    now_[p] = z;
    now_max_.mark(p);
  }
}

void TranslucentTile::begin_pass() {
  now_ = gone_;
  now_max_.mark_all();
  ++S_->passes;
}

// The tile's spheres in bin order (nearest depth first); each is set up only
// when a pass reaches it, so spheres a pass never reaches cost little.
void TranslucentTile::gather_live(Which which) {
  const SphereGrid& g = *f_->g;
  live_.clear();
  for (uint64_t q = 0; q < count_; ++q) {
    const uint32_t e = bin_[q], id = g.ids[e];
    const double al = alpha(id);
    if (al == 0) continue;  // (the renderer bins none)
    const bool opaque = al == 1;
    if ((which == Which::Opaque && !opaque) || (which == Which::Translucent && opaque)) continue;
    const double zmin = to_camera(*f_->view, g.centre[e]).z - g.radius[e];
    Live L;
    L.z_reject = zmin - 1e-9 * std::abs(zmin);  // no computed depth of the sphere is nearer
    L.e = e;
    L.id = id;
    L.opaque = opaque;
    L.ready = false;
    live_.push_back(L);
  }
}

bool TranslucentTile::set_up(Live& L) const {
  const SphereGrid& g = *f_->g;
  const glm::dvec3 c = to_camera(*f_->view, g.centre[L.e]);
  L.su = setup_sphere(f_->cam, c.x, c.y, c.z, g.radius[L.e]);
  if (!sphere_pixel_range(L.su, vp_, &L.i0, &L.i1, &L.j0, &L.j1)) return false;
  L.i0 -= vp_.x0, L.i1 -= vp_.x0, L.j0 -= vp_.y0, L.j1 -= vp_.y0;
  L.ready = true;
  return true;
}

double TranslucentTile::now_tile_max() {
  const int bw = int((w_ + kTileBlock - 1) / kTileBlock), bh = int((h_ + kTileBlock - 1) / kTileBlock);
  double m = -INFINITY;
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      m = std::max(m, now_max_.get(now_.data(), bx, by));
      if (m == INFINITY) return m;
    }
  return m;
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
  kfirst_.assign(n, kKeyMax);
  gone_.assign(n, INFINITY);
  now_.assign(n, INFINITY);
  gone_max_.reset(w_, h_);
  now_max_.reset(w_, h_);
  prev_.assign(n, kKeyMin);
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
  const size_t n = size_t(w_) * h_;
  kcount_.resize(n);
  kslot_.resize(n);
  kcut_.resize(n);
  gather_live(Which::All);
  uint64_t K = kSortedLayers;
  for (bool first = true; !live_.empty(); first = false) {
    // Slots for the open pixels only; K grows once the first pass has
    // shown which pixels are deep.
    size_t open = 0;
    for (size_t p = 0; p < n; ++p)
      if (gone_[p] != -INFINITY) kslot_[p] = uint32_t(open++);
    if (open == 0) break;
    if (!first) {
      const uint64_t fit = f_->kbuf_bytes / (uint64_t(open) * sizeof(FragKey));
      K = std::max<uint64_t>(K, std::min<uint64_t>({K * 64, fit, uint64_t(1) << 24}));
    }
    kbuf_.resize(open * K);
    begin_pass();
    std::fill(kcount_.begin(), kcount_.end(), 0);
    std::fill(kcut_.begin(), kcut_.end(), kKeyMax);
    // Per open pixel, every fragment behind the last one composited and in
    // front of its cut (+inf at first). A full buffer keeps its nearest half
    // (nth_element: sequential, amortised O(1) per fragment, unlike a heap's
    // cache misses) and the cut moves to the first fragment dropped; the
    // cut's depth is the pass's `now`. An opaque fragment also bounds the
    // pixel for good.
    pass([&](size_t p, const FragKey& k, bool opaque) {
      if (!(prev_[p] < k) || k.z > gone_[p]) return false;
      if (!(k < kcut_[p])) return true;  // for a later pass
      if (opaque) set_gone(p, k.z);       // nothing behind it counts, in any pass
      FragKey* b = &kbuf_[kslot_[p] * K];
      uint32_t c = kcount_[p];
      if (c == K) {
        const uint32_t half = uint32_t(K / 2);
        std::nth_element(b, b + half, b + K);
        kcut_[p] = b[half];
        set_now(p, b[half].z);
        c = half;
        if (!(k < kcut_[p])) {
          kcount_[p] = c;
          return true;
        }
      }
      b[c] = k;
      kcount_[p] = c + 1;
      return true;
    });
    bool more = false;
    for (size_t p = 0; p < n; ++p) {
      if (gone_[p] == -INFINITY) continue;
      const uint32_t c = kcount_[p];
      FragKey* b = &kbuf_[kslot_[p] * K];
      std::sort(b, b + c);
      double* a = &acc_[p * 4];
      bool done = kcut_[p] == kKeyMax;  // it had no more fragments than these
      for (uint32_t i = 0; i < c; ++i) {
        double col[4];
        color(p, b[i], col);
        note_first(p, b[i]);
        composite_under(a, col);
        ++S_->composited;
        prev_[p] = b[i];
        if (col[3] == 1.0 || opaque_now(a)) {
          done = true;
          break;
        }
        if (saturated(a, stop_)) {
          ++S_->pixels_stopped;
          done = true;
          break;
        }
      }
      if (done)
        set_gone(p, -INFINITY);
      else
        more = true;
    }
    if (!more) break;
  }
}

// The composite over the image background; RGBA + Z out.
void TranslucentTile::finish() {
  const size_t n = size_t(w_) * h_;
  const size_t C = f_->ao ? 6 : 5;
  out_.resize(n * C);
  const double* bg = f_->rs->background;
  for (size_t p = 0; p < n; ++p) {
    float* o = &out_[p * C];
    double* a = &acc_[p * 4];
    if (f_->rs->mode != SphereMode::Weighted) composite_under(a, bg);
    for (int k = 0; k < 4; ++k) o[k] = float(a[k]);
    o[4] = float(zfirst_[p]);
    if (f_->ao) o[5] = zfirst_[p] == INFINITY ? INFINITY : float(fragment_ao(p, kfirst_[p]));
    if (zfirst_[p] != INFINITY) ++S_->rendered_pixels;
  }
}

}  // namespace zs
