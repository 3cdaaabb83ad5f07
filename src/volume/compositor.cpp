#include "volume/compositor.h"

namespace zs {

namespace {
// After a fragment: the inside count and where the next segment starts.
inline void step_past(PixelRecord& px, const Fragment& f) {
  if (f.kind == kEntry) {
    if (px.inside < INT16_MAX) ++px.inside;
  } else if (f.kind == kExit) {
    // Clamped: an exit with no matching entry (a ray grazing a silhouette
    // vertex or edge, which has zero length inside) must not go negative.
    if (px.inside > 0) --px.inside;
  }
  px.last_z = f.z;
  px.last_s = f.s;
}
}  // namespace

void Compositor::composite(PixelRecord& px, FragmentPool& pool, float z_limit, int X, int Y) {
  if (px.done) {
    pool.clear(px);
    return;
  }
  // Perspective rays are longer than their depth span by a per-pixel factor.
  const double len_factor = view_.perspective() ? view_.ray_length_factor(double(X), double(Y)) : 1.0;
  while (px.head != kNil) {
    const Fragment f = pool.at(px.head);
    if (!(f.z < z_limit)) break;
    pool.pop_front(px);
    if (batch_) {
      // Deferred: the segment needs only its ends (segment_batch.h).
      if (px.inside > 0 && f.z > px.last_z) {
        if (batch_->full()) batch_->flush(records_);
        batch_->push(uint32_t(&px - records_), px.last_s, f.s, double(f.z - px.last_z) * len_factor);
        ++segments_;
      }
      step_past(px, f);
      continue;
    }
    const SegmentEnd end = integ_.end(f.s);
    if (px.inside > 0 && f.z > px.last_z) {
      const SegmentLight seg = integ_.integrate(px.last_s, SegmentEnd{px.last_k, px.last_L}, f.s, end,
                                                double(f.z - px.last_z) * len_factor);
      const double T = px.T;
      px.rgb[0] += T * seg.rgb[0];
      px.rgb[1] += T * seg.rgb[1];
      px.rgb[2] += T * seg.rgb[2];
      px.T = T * seg.T;
      ++segments_;
      if (px.T < et_) {
        px.done = 1;
        ++terminated_;
        pool.clear(px);
        return;
      }
    }
    step_past(px, f);
    px.last_k = int16_t(end.k);
    px.last_L = end.L;
  }
}

}  // namespace zs
