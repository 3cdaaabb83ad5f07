#include "render/volume/compositor.h"

namespace zs {

void Compositor::composite(PixelRecord& px, PixelLists& lists, float z_limit, int X, int Y) {
  if (px.done) {
    lists.clear(px);
    return;
  }
  // Perspective rays are longer than their depth span by a per-pixel factor.
  const double len_factor = view_.perspective() ? view_.ray_length_factor(double(X), double(Y)) : 1.0;
  if (batch_) {  // deferred: the segment needs only its ends (segment_batch.h)
    composite_batched(px, uint32_t(&px - records_), lists, z_limit, len_factor);
    return;
  }
  // The segment start's end values are recomputed from its scalar (the same
  // bits the previous fragment gave): this path runs only with early
  // termination or the approximate integrators.
  while (px.n > 0 && px.z[0] < z_limit) {
    const float z = px.z[0], s = px.s[0];
    const uint32_t kind = px.kind(0);
    lists.drop_front(px, 1);
    Cut k{px.last_s, held_ ? px.last_s : s, double(z - px.last_z)};
    if (px.inside > 0 && z > px.last_z &&
        (!clip_ || cut(uint32_t(&px - records_), px.last_z, px.last_s, z, float(k.s1), &k))) {
      const SegmentLight seg = integ_.integrate(k.s0, integ_.end(k.s0), k.s1, integ_.end(k.s1), k.dz * len_factor);
      PixelLight& l = lights_[&px - records_];
      const double T = l.T;
      l.rgb[0] += T * seg.rgb[0];
      l.rgb[1] += T * seg.rgb[1];
      l.rgb[2] += T * seg.rgb[2];
      l.T = T * seg.T;
      ++segments_;
      if (l.T < et_) {
        px.done = 1;
        ++terminated_;
        lists.clear(px);
        return;
      }
    }
    step_past(px, z, s, kind);
  }
}

}  // namespace zs
