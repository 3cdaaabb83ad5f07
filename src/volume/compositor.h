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
#include <vector>

#include "raster/raster_target.h"
#include "scene/camera.h"
#include "volume/pixel_lists.h"
#include "volume/segment_integrator.h"

namespace zs {

class Compositor {
 public:
  // et_transmittance: stop a pixel once its transmittance is below this (0 = never).
  Compositor(const View& view, const Viewport& vp, const SegmentIntegrator& integ, double et_transmittance);

  // Composites pixel p's fragments with depth < z_limit (all if z_limit is +inf).
  void composite(PixelLists& lists, uint32_t p, float z_limit);
  bool done(uint32_t p) const { return done_[p] != 0; }

  uint32_t num_pixels() const { return n_; }
  double transmittance(uint32_t p) const { return T_[p]; }
  const double* rgb(uint32_t p) const { return &rgb_[3 * size_t(p)]; }

  uint64_t segments() const { return segments_; }
  uint64_t terminated_pixels() const { return terminated_; }

 private:
  const View& view_;
  Viewport vp_;
  uint32_t w_, n_;
  const SegmentIntegrator& integ_;
  double et_;
  std::vector<double> rgb_, T_;
  std::vector<float> last_z_, last_s_;
  std::vector<int32_t> inside_;
  std::vector<uint8_t> done_;
  uint64_t segments_ = 0, terminated_ = 0;
};

}  // namespace zs
