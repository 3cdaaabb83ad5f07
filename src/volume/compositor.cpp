#include "volume/compositor.h"

namespace zs {

Compositor::Compositor(const View& view, const Viewport& vp, const SegmentIntegrator& integ, double et)
    : view_(view), vp_(vp), w_(uint32_t(vp.x1 - vp.x0)), n_(uint32_t(vp.x1 - vp.x0) * uint32_t(vp.y1 - vp.y0)),
      integ_(integ), et_(et), rgb_(3 * size_t(n_), 0.0), T_(n_, 1.0), last_z_(n_, 0.f), last_s_(n_, 0.f),
      inside_(n_, 0), done_(n_, 0) {}

void Compositor::composite(PixelLists& lists, uint32_t p, float z_limit) {
  if (done_[p]) {
    lists.clear(p);
    return;
  }
  const double X = double(vp_.x0 + int(p % w_)), Y = double(vp_.y0 + int(p / w_));
  const double len_factor = view_.ray_length_factor(X, Y);
  double* rgb = &rgb_[3 * size_t(p)];
  for (uint32_t idx = lists.head(p); idx != kNil; idx = lists.head(p)) {
    const Fragment f = lists.at(idx);
    if (!(f.z < z_limit)) break;
    lists.pop_front(p);
    if (inside_[p] > 0 && f.z > last_z_[p]) {
      const SegmentLight seg = integ_.integrate(last_s_[p], f.s, double(f.z - last_z_[p]) * len_factor);
      const double T = T_[p];
      rgb[0] += T * seg.rgb[0];
      rgb[1] += T * seg.rgb[1];
      rgb[2] += T * seg.rgb[2];
      T_[p] = T * seg.T;
      ++segments_;
      if (T_[p] < et_) {
        done_[p] = 1;
        ++terminated_;
        lists.clear(p);
        return;
      }
    }
    if (f.kind == kEntry) {
      ++inside_[p];
    } else if (f.kind == kExit) {
      // Clamped: an exit with no matching entry (a ray grazing a silhouette
      // vertex or edge, which has zero length inside) must not go negative.
      if (inside_[p] > 0) --inside_[p];
    }
    last_z_[p] = f.z;
    last_s_[p] = f.s;
  }
}

}  // namespace zs
