// Delayed compositing (digest §1.1 stage 3): consumes a pixel's fragments in
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

#include "scene/camera.h"
#include "volume/pixel_lists.h"
#include "volume/segment_batch.h"
#include "volume/segment_integrator.h"

namespace zs {

class Compositor {
 public:
  // et_transmittance: stop a pixel once its transmittance is below this (0 =
  // never). With a batch (exact integrator, no early termination: nothing
  // reads a pixel's colour before the tile ends), segments are queued there
  // and composited into records[pixel] in order when it fills or on flush().
  Compositor(const View& view, const SegmentIntegrator& integ, double et_transmittance,
             SegmentBatch* batch = nullptr, PixelRecord* records = nullptr)
      : view_(view), integ_(integ), et_(et_transmittance), batch_(batch), records_(records) {}
  void flush() {
    if (batch_) batch_->flush(records_);
  }

  // Composites the fragments of the pixel at image coordinates (X, Y) with
  // depth < z_limit (all if z_limit is +inf), freeing them.
  void composite(PixelRecord& px, FragmentPool& pool, float z_limit, int X, int Y);

  uint64_t segments() const { return segments_; }
  uint64_t terminated_pixels() const { return terminated_; }

 private:
  const View& view_;
  const SegmentIntegrator& integ_;
  double et_;
  SegmentBatch* batch_;
  PixelRecord* records_;
  uint64_t segments_ = 0, terminated_ = 0;
};

}  // namespace zs
