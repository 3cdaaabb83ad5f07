// What a volume render needs besides the mesh: view, image, optics, and the
// knobs a user trades speed against accuracy with.
#pragma once

#include <cstdint>
#include <string>

#include "raster/bconvert_scan.h"
#include "raster/triangle_scan.h"
#include "base/optics/segment_integrator.h"
#include "base/optics/transfer_function.h"
#include "render/frame_settings.h"

namespace zs {

// The frame (size, background, camera, threads, tiles, budget) and the
// volume's own: optics, scan strategy, integrator and accuracy trades.
struct RenderSettings : FrameSettings {
  TransferFunction tf;
  ScanStrategy scan = ScanStrategy::Span;  // exact and the fastest; bbox gives the same image
  BConvertVariant bconvert_variant = BConvertVariant::Truncate;
  Integrator integrator = Integrator::Exact;
  // The exact integrator's batched kernel in single precision: twice the
  // segments per vector, each segment's light within docs/accuracy.md's
  // bound (not bit-identical to double). Used where segments are batched
  // (exact, no early termination); elsewhere the double integrator runs.
  bool single_precision = false;
  // Early termination threshold t in 8-bit levels: stop a pixel once its
  // transmittance is below t/510, which bounds the error by t/2 levels
  // (the spheres digest's bound, §2.3.7). 0 = off.
  double early_termination = 0;
  uint32_t max_list_length = 0;         // 0 = unlimited
  // Benchmarks: scan-convert every face but keep no fragments (no lists, no
  // compositing; the image is the background).
  bool raster_only = false;
  // Sum screen face and bounding-box areas (Table 4.4); off in plain renders
  // so the per-face hot path does not pay three square roots for a statistic.
  bool face_area_stats = false;
  // Time the per-face phases (list generation, scan, insert, composite):
  // four clock reads per face, so only the benchmarks that report them ask.
  bool phase_times = false;
};

}  // namespace zs
