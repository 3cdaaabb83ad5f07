#include "volume/compositor.h"

namespace zs {

void Compositor::composite(PixelRecord& px, FragmentPool& pool, float z_limit, int X, int Y) {
  if (px.done) {
    pool.clear(px);
    return;
  }
  // Perspective rays are longer than their depth span by a per-pixel factor.
  const double len_factor = view_.perspective() ? view_.ray_length_factor(double(X), double(Y)) : 1.0;
  if (batch_) {  // deferred: the segment needs only its ends (segment_batch.h)
    composite_batched(px, uint32_t(&px - records_), pool, z_limit, len_factor);
    return;
  }
  while (px.head != kNil) {
    const Fragment f = pool.at(px.head);
    if (!(f.z < z_limit)) break;
    pool.pop_front(px);
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
