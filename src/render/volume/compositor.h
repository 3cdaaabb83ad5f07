// Delayed compositing (B-Convert digest §1.1, stage 3): consumes a pixel's fragments in
// depth order and integrates each segment between consecutive fragments that
// lies inside the (visible) mesh, front to back.
//
// Inside-ness is a per-pixel count: an entry fragment adds one, an exit
// fragment removes one, and only segments that start with a positive count
// are integrated. So the gap between an exit face and the next entry face of
// a non-convex mesh is never integrated, and coincident exit/entry pairs (a
// seam) cost a zero-length segment whichever order they come in.
#pragma once

#include <cstdint>

#include "base/view/camera.h"
#include "render/volume/pixel_lists.h"
#include "render/volume/segment_batch.h"
#include "base/optics/segment_integrator.h"

namespace zs {

class Compositor {
 public:
  // records / lights: the tile's pixel records and their accumulators, both
  // indexed by pixel. et_transmittance: stop a pixel once its transmittance
  // is below this (0 = never). With a batch (exact integrator, no early
  // termination: nothing reads a pixel's colour before the tile ends),
  // segments are queued there and composited into lights[pixel] in order
  // when it fills or on flush().
  // held: cell data — each segment's scalar is its front fragment's, held
  // over the whole segment (the tet's own value; face_classes.h). clip: per
  // pixel, the depth interval the clip planes keep, ending at the opaque
  // geometry under the volume (two floats, in the fragments' depth units;
  // null: neither); segments are cut to it.
  Compositor(const View& view, const SegmentIntegrator& integ, double et_transmittance, SegmentBatch* batch,
             PixelRecord* records, PixelLight* lights, bool held = false, const float* clip = nullptr)
      : view_(view), integ_(integ), et_(et_transmittance), batch_(batch), records_(records), lights_(lights),
        held_(held), clip_(clip) {}
  void flush() {
    if (batch_) batch_->flush(lights_);
  }

  // Composites the fragments of the pixel at image coordinates (X, Y) with
  // depth < z_limit (all if z_limit is +inf), freeing them.
  void composite(PixelRecord& px, PixelLists& lists, float z_limit, int X, int Y);
  // The same on the batched path (batched() true): segments are queued under
  // `pixel` (px = records[pixel]); len_factor: ray length per unit depth.
  // Inline: it runs for most fragments.
  bool batched() const { return batch_ != nullptr; }
  void composite_batched(PixelRecord& px, uint32_t pixel, PixelLists& lists, float z_limit, double len_factor) {
    for (;;) {
      const int n = px.n;
      int i = 0;
      for (; i < n && px.z[i] < z_limit; ++i) {
        const float z = px.z[i];
        if (px.inside > 0 && z > px.last_z) {
          const float s1 = held_ ? px.last_s : px.s[i];
          if (!clip_) {
            if (batch_->full()) batch_->flush(lights_);
            batch_->push(pixel, px.last_s, s1, double(z - px.last_z) * len_factor);
            ++segments_;
          } else {
            Cut k;
            if (cut(pixel, px.last_z, px.last_s, z, s1, &k)) {
              if (batch_->full()) batch_->flush(lights_);
              batch_->push(pixel, k.s0, k.s1, k.dz * len_factor);
              ++segments_;
            }
          }
        }
        step_past(px, z, px.s[i], px.kind(i));
      }
      if (i == 0) return;
      lists.drop_front(px, i);
      // Everything inline was final: go on with what moved up from the overflow.
      if (i < n || px.n == 0) return;
    }
  }

  // After a fragment: the inside count and where the next segment starts.
  // An entry adds one (saturating), an exit removes one but never below zero
  // (an exit with no matching entry — a ray grazing a silhouette vertex or
  // edge, which has zero length inside — must not go negative); branch-free,
  // as the kind is as good as random.
  static void step_past(PixelRecord& px, float z, float s, uint32_t kind) {
    const int inside = int(px.inside) + int(kind) - int(kInterior);
    px.inside = int16_t(inside < 0 ? 0 : inside > INT16_MAX ? INT16_MAX : inside);
    px.last_z = z;
    px.last_s = s;
  }

  // A segment from (z0, s0) to (z1, s1) cut to pixel p's clip interval:
  // false when nothing is left; the scalar stays linear (held: constant).
  struct Cut {
    double s0, s1, dz;
  };
  bool cut(uint32_t p, float z0, float s0, float z1, float s1, Cut* out) {
    const float lo = clip_[2 * p], hi = clip_[2 * p + 1];
    if (z0 >= lo && z1 <= hi) {  // wholly kept: the uncut segment's numbers
      *out = {s0, s1, double(z1 - z0)};
      return true;
    }
    ++clipped_;
    const float a = z0 < lo ? lo : z0, b = z1 > hi ? hi : z1;
    if (!(b > a)) return false;
    const double ds = (double(s1) - s0) / (double(z1) - z0);
    out->s0 = a == z0 ? double(s0) : s0 + ds * (double(a) - z0);
    out->s1 = b == z1 ? double(s1) : s0 + ds * (double(b) - z0);
    out->dz = double(b - a);
    return true;
  }

  uint64_t segments() const { return segments_; }
  uint64_t clipped_segments() const { return clipped_; }
  uint64_t terminated_pixels() const { return terminated_; }

 private:
  const View& view_;
  const SegmentIntegrator& integ_;
  double et_;
  SegmentBatch* batch_;
  PixelRecord* records_;
  PixelLight* lights_;
  bool held_;
  const float* clip_;
  uint64_t segments_ = 0, terminated_ = 0, clipped_ = 0;
};

}  // namespace zs
