#include "render/volume/tile_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "base/util/bytes_str.h"
#include "render/volume/compositor.h"
#include "render/volume/render_stats.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The sweep of one tile, with its state in one place.
class TileSweep {
 public:
  TileSweep(const SweepShared& in, uint32_t tile, const Viewport& vp, uint64_t max_fragments, TileWorkspace& ws,
            RenderStats& S)
      : in_(in), rs_(in.rs), vp_(vp), vw_(uint32_t(vp.x1 - vp.x0)), ws_(ws), S_(S),
        npix_(size_t(vw_) * uint32_t(vp.y1 - vp.y0)), records_(prepare(ws, npix_)),
        under_(in.under ? in.under->tile(tile) : nullptr), clip_(clip_for(in, under_, vp, vw_, npix_, ws)),
        comp_(in.view, in.integ, rs_.early_termination > 0 ? rs_.early_termination / 510.0 : 0.0,
              batch_for(in, ws), records_, ws.light.data(), in.cell != nullptr,  // after prepare() sized ws.light
              clip_),
        timed_(rs_.phase_times) {
    ws.active.clear();
    ws.touched.clear();
    ws.lists.reset(max_fragments);
    if (!ws.scanner)
      ws.scanner = std::make_unique<TriangleScanner>(rs_.scan, rs_.bconvert_variant,
                                                     Viewport{0, 0, int(rs_.width), int(rs_.height)});
  }

  // Exact integration without early termination is deferred and batched.
  static SegmentBatch* batch_for(const SweepShared& in, TileWorkspace& ws) {
    if (in.rs.integrator != Integrator::Exact || in.rs.early_termination > 0) return nullptr;
    if (!ws.batch)
      ws.batch = std::make_unique<SegmentBatch>(
          in.integ, in.rs.tf, best_kernel_width(),
          in.rs.single_precision ? KernelPrecision::Single : KernelPrecision::Double);
    return ws.batch.get();
  }
  // The depth interval each pixel's ray keeps of the clip region, up to the
  // opaque geometry under it, relative to z_origin as fragments are (null:
  // neither).
  static const float* clip_for(const SweepShared& in, const float* under, const Viewport& vp, uint32_t vw,
                               size_t npix, TileWorkspace& ws) {
    const ClipRegion& region = in.rs.clip;
    if (region.empty() && !under) return nullptr;
    const uint32_t stride = under ? in.under->stride() : 0;
    ws.clip.resize(2 * npix);
    for (size_t p = 0; p < npix; ++p) {
      double lo = -INFINITY, hi = INFINITY;
      bool kept = true;
      if (!region.empty()) {
        glm::dvec3 at, per;
        in.view.depth_line(double(vp.x0 + int(p % vw)), double(vp.y0 + int(p / vw)), &at, &per);
        kept = region.interval(at, per, &lo, &hi);
      }
      if (under) hi = std::min(hi, double(under[p * stride + 4]));  // the ray stops at the geometry
      kept = kept && lo <= hi;
      ws.clip[2 * p] = kept ? float(lo - in.z_origin) : INFINITY;
      ws.clip[2 * p + 1] = kept ? float(hi - in.z_origin) : -INFINITY;
    }
    return ws.clip.data();
  }

  // Records are indexed row by row within the tile (any tile size fits in
  // records that are all reset). finish() resets the ones a tile touched.
  static PixelRecord* prepare(TileWorkspace& ws, size_t npix) {
    if (ws.px.size() < npix) {
      ws.px.resize(npix);
      ws.light.resize(npix);
      ws.px_clean = false;
    }
    if (!ws.px_clean) {
      for (PixelRecord& p : ws.px) p.reset();
      for (PixelLight& l : ws.light) l.reset();
    }
    ws.px_clean = false;  // until finish() has reset what this tile touches
    return ws.px.data();
  }

  // Copies the next n items of the bin, with their vertices, into the
  // thread's staging buffer. A face's vertices are dependent reads away from
  // its bin entry (item, face, tet, vertices), each a cache miss on a large
  // mesh; in this short loop of loads the misses of many items overlap,
  // where in the sweep each would stall the scan of its face.
  void stage(uint64_t b0, size_t n) {
    const Topology& topo = in_.topo;
    StagedItem* st = ws_.staged.data();
    for (size_t i = 0; i < n; ++i) {
      const SweepItem& item = in_.items[in_.bins.items[b0 + i]];
      st[i].id = item.id;
      st[i].z_sweep = item.z_sweep;
      if (!(item.id & kNearItem)) {
        const auto fv = topo.face(item.id);
        for (int c = 0; c < 3; ++c) st[i].vid[c] = fv[c];
      }
    }
    for (size_t i = 0; i < n; ++i) {
      StagedItem& it = st[i];
      if (it.id & kNearItem) {
        const NearTriangle& nt = in_.near[it.id & ~kNearItem];
        for (int c = 0; c < 3; ++c) it.tri[c] = nt.v[c];
        it.cls = nt.cls;
      } else {
        for (int c = 0; c < 3; ++c) it.tri[c] = in_.sv[it.vid[c]];
        it.cls = in_.cls[it.id];
        if (in_.cell) {
          // Cell data: the face's value is its tet's (face_classes.h), one
          // plane of constant scalar.
          const double s = in_.cell[value_from_tet1(it.cls) ? in_.topo.tet1(it.id) : in_.topo.tet0(it.id)];
          for (int c = 0; c < 3; ++c) it.tri[c].s = s;
        }
      }
    }
  }

  void run(uint32_t tile) {
    const auto& bins = in_.bins;
    float z_target = -INFINITY;
    const uint64_t b_end = bins.offset[tile + 1];
    for (uint64_t b0 = bins.offset[tile]; b0 < b_end; b0 += kStage) {
      const size_t n = size_t(std::min<uint64_t>(kStage, b_end - b0));
      stage(b0, n);
      for (size_t i = 0; i < n; ++i) {
        const StagedItem& it = ws_.staged[i];
        if (it.z_sweep > z_target) {
          // The sweep passed z_target: every face still to come starts at or
          // after z_sweep, so every fragment before it is final. Composite them
          // all and aim at the farthest vertex of the faces now being projected.
          if (!ws_.active.empty()) {
            ++S_.composite_events;
            composite_all(it.z_sweep);
          }
          z_target = it.z_sweep;
        }
        z_target = std::max(z_target, item_z_max(it.tri, in_.z_origin));
        project(it.tri, it.cls, it.z_sweep);
      }
    }
    composite_all(INFINITY);
    comp_.flush();
    S_.fragments += fragments_;
    S_.max_list_length = std::max(S_.max_list_length, max_len_);
    S_.segments += comp_.segments();
    S_.segments_clipped += comp_.clipped_segments();
    S_.early_terminated_pixels += comp_.terminated_pixels();
    S_.peak_fragments = std::max<uint64_t>(S_.peak_fragments, ws_.lists.peak_fragments());
    S_.peak_overflow_fragments = std::max<uint64_t>(S_.peak_overflow_fragments, ws_.lists.peak_overflow_fragments());
    S_.bconvert_fallbacks += ws_.scanner->take_bconvert_fallbacks();
    const RowEndMisses re = ws_.scanner->take_row_end_misses();
    for (int k = 0; k < 4; ++k) S_.row_end_misses[k] += re.count[k];
    finish();
  }

 private:
  // Composites pixel p's fragments before z_limit; (X, Y): its image coordinates.
  void composite_pixel(PixelRecord& px, uint32_t p, int X, int Y, float z_limit) {
    if (comp_.batched())
      comp_.composite_batched(px, p, ws_.lists, z_limit,
                              in_.view.perspective() ? in_.view.ray_length_factor(double(X), double(Y)) : 1.0);
    else
      comp_.composite(px, ws_.lists, z_limit, X, Y);
  }

  void composite_all(float z_limit) {
    const auto t0 = timed_ ? Clock::now() : Clock::time_point{};
    size_t n = 0;
    for (uint32_t p : ws_.active) {
      PixelRecord& px = ws_.px[p];
      composite_pixel(px, p, vp_.x0 + int(p % vw_), vp_.y0 + int(p / vw_), z_limit);
      if (px.n > 0) ws_.active[n++] = p;
      else px.active = 2;
    }
    ws_.active.resize(n);
    if (timed_) S_.ms_composite += ms_between(t0, Clock::now());
  }

  // Lists pixel p among the active ones (and, the first time, the touched ones).
  void activate(PixelRecord& px, uint32_t p) {
    if (px.active == 0) ws_.touched.push_back(p);
    px.active = 1;
    ws_.active.push_back(p);
  }

  // Counts of one face's fragments, kept in registers by the hot loop and
  // added up once per face.
  struct FaceCounts {
    uint64_t inserted = 0;
    uint32_t max_len = 0;
  };

  // One fragment for pixel p at image coordinates (X, Y): the per-fragment
  // path of the whole engine.
  void add_fragment(uint32_t p, int X, int Y, float z, float s, uint32_t kind, float z_sweep,
                    uint32_t max_list_length, FaceCounts& fc) {
    PixelRecord& px = ws_.px[p];
    if (px.done) return;  // early-terminated: nothing behind matters
    // Fragments this pixel holds before the sweep plane are final: composite
    // them now, while the record is in cache.
    if (px.z[0] < z_sweep) {
      composite_pixel(px, p, X, Y, z_sweep);
      if (px.done) return;
    }
    if (!ws_.lists.insert(px, z, s, kind)) insert_over_budget(px, z, s, kind, z_sweep, fc.inserted);
    if (px.active != 1) activate(px, p);
    ++fc.inserted;
    fc.max_len = std::max<uint32_t>(fc.max_len, px.pending());
    if (max_list_length && px.pending() > max_list_length) {
      ++S_.forced_composites;  // force this pixel's final fragments out now
      composite_pixel(px, p, X, Y, z_sweep);
    }
  }
  void end_face(const FaceCounts& fc) {
    ws_.lists.add_live(fc.inserted);
    fragments_ += fc.inserted;
    max_len_ = std::max<uint64_t>(max_len_, fc.max_len);
  }

  // Overflow pool at its budget: composite everything already final (before
  // the sweep plane) everywhere, then retry once.
  [[gnu::noinline]] void insert_over_budget(PixelRecord& px, float z, float s, uint32_t kind, float z_sweep,
                                            uint64_t face_inserted) {
    ++S_.budget_flushes;
    composite_all(z_sweep);
    if (!ws_.lists.insert(px, z, s, kind))
      throw std::runtime_error("memory budget too small: " +
                               std::to_string(ws_.lists.live_fragments() + face_inserted) + " fragments (" +
                               bytes_str(ws_.lists.overflow_fragments() * sizeof(Fragment)) +
                               " beyond the pixel records) must be pending at once in one tile of this view");
  }

  // Scan-converts one triangle inside the tile and inserts its fragments
  // (z_sweep: the depth before which every fragment is final).
  void project(const ScreenVertex tri[3], FaceClass fclass, float z_sweep) {
    // list_generation: per-face set-up (plane equations; B-Convert's edge
    // and compact lists); scan_convert: finding the pixels and interpolating
    // depth and scalar there; insert: the pixel lists.
    const auto t0 = timed_ ? Clock::now() : Clock::time_point{};
    ScreenTriangle st;
    const bool ok = setup_triangle(tri, in_.view.perspective(), &st);
    ws_.scanner->prepare(tri, ok);
    const auto t1 = timed_ ? Clock::now() : Clock::time_point{};
    if (timed_) S_.ms_list_generation += ms_between(t0, t1);
    if (!ok) {
      ++S_.faces_degenerate;
      return;
    }
    ++S_.faces_projected;
    if (rs_.face_area_stats) add_face_area(tri, st);
    FaceSpans& spans = ws_.spans;
    spans.clear();
    ScanCounters sc;
    ws_.scanner->scan(st, vp_, spans, sc);
    S_.pixel_tests += sc.pixel_tests;
    S_.pixel_hits += sc.pixel_hits;
    S_.pixel_misses += sc.pixel_misses;
    const FaceClass base = base_class(fclass);
    const uint32_t kind = base == FaceClass::Entry ? kEntry : base == FaceClass::Exit ? kExit : kInterior;
    const double z_origin = in_.z_origin;
    if (timed_ || rs_.raster_only) {
      // The benchmarks' path: fragments first (timed as scan conversion), then insertion.
      FaceFragments& frags = ws_.frags;
      frags.clear();
      expand_spans(st, spans, frags);
      const auto t2 = timed_ ? Clock::now() : Clock::time_point{};
      if (timed_) S_.ms_scan_convert += ms_between(t1, t2);
      if (rs_.raster_only) return;
      FaceCounts fc;
      for (size_t k = 0; k < frags.size(); ++k)
        add_fragment(uint32_t(frags.y[k] - vp_.y0) * vw_ + uint32_t(frags.x[k] - vp_.x0), frags.x[k], frags.y[k],
                     float(frags.z[k] - z_origin), float(frags.s[k]), kind, z_sweep, rs_.max_list_length, fc);
      end_face(fc);
      if (timed_) S_.ms_insert += ms_between(t2, Clock::now());
      return;
    }
    // Renders: each fragment goes from its span to its list directly, in a
    // loop built for the common case (orthographic, batched compositing, no
    // list limit) so it carries no test that cannot change within a render.
    if (!st.perspective && comp_.batched() && !rs_.max_list_length)
      insert_spans_ortho_batched(st, kind, z_sweep);
    else
      insert_spans(st, kind, z_sweep);
  }

  void insert_spans(const ScreenTriangle& st, uint32_t kind, float z_sweep) {
    FaceCounts fc;
    const uint32_t max_list_length = rs_.max_list_length;
    const double z_origin = in_.z_origin;
    for (const RowSpan& r : ws_.spans.rows) {
      const uint32_t row = uint32_t(r.y - vp_.y0) * vw_;
      for (int32_t i = r.x0; i <= r.x1; ++i) {
        double z, s;
        st.attributes(double(i), double(r.y), &z, &s);
        add_fragment(row + uint32_t(i - vp_.x0), i, r.y, float(z - z_origin), float(s), kind, z_sweep,
                     max_list_length, fc);
      }
    }
    end_face(fc);
  }

  // insert_spans and add_fragment for orthographic views on the batched path
  // without a list limit: the same operations in the same order (the same
  // image, bit for bit), with every per-render test hoisted out.
  void insert_spans_ortho_batched(const ScreenTriangle& st, uint32_t kind, float z_sweep) {
    FaceCounts fc;
    const double z_origin = in_.z_origin;
    PixelRecord* const px0 = ws_.px.data();
    PixelLists& lists = ws_.lists;
    const double x0 = st.x0, y0 = st.y0, q_c = st.q_c, q_gx = st.q_gx, q_gy = st.q_gy;
    const double r_c = st.r_c, r_gx = st.r_gx, r_gy = st.r_gy;
    const double z_lo = st.z_lo, z_hi = st.z_hi, s_lo = st.s_lo, s_hi = st.s_hi;
    for (const RowSpan& r : ws_.spans.rows) {
      const uint32_t row = uint32_t(r.y - vp_.y0) * vw_ - uint32_t(vp_.x0);
      const double dy = double(r.y) - y0;
      const double q_row = q_gy * dy, r_row = r_gy * dy;
      for (int32_t i = r.x0; i <= r.x1; ++i) {
        // ScreenTriangle::attributes, orthographic: (c + gx·dx) + gy·dy.
        const double dx = double(i) - x0;
        const float z = float(std::clamp((q_c + q_gx * dx) + q_row, z_lo, z_hi) - z_origin);
        const float s = float(std::clamp((r_c + r_gx * dx) + r_row, s_lo, s_hi));
        const uint32_t p = row + uint32_t(i);
        PixelRecord& px = px0[p];
        if (px.z[0] < z_sweep) comp_.composite_batched(px, p, lists, z_sweep, 1.0);
        uint32_t len = lists.insert_counted(px, z, s, kind);
        if (!len) {
          insert_over_budget(px, z, s, kind, z_sweep, fc.inserted);
          len = px.pending();
        }
        if (px.active != 1) activate(px, p);
        fc.max_len = std::max(fc.max_len, len);
      }
      fc.inserted += uint64_t(r.x1 - r.x0 + 1);
    }
    end_face(fc);
  }

  // Heron's formula on the screen edges (Eqs. 4.1-4.3) and the box area,
  // for the face / bounding-box ratio of Table 4.4.
  void add_face_area(const ScreenVertex tri[3], const ScreenTriangle& st) {
    // sqrt of the squares, not hypot (several times slower, and a statistic
    // has no use for hypot's care near overflow).
    auto len = [](double dx, double dy) { return std::sqrt(dx * dx + dy * dy); };
    const double e0 = len(tri[1].x - tri[0].x, tri[1].y - tri[0].y);
    const double e1 = len(tri[2].x - tri[1].x, tri[2].y - tri[1].y);
    const double e2 = len(tri[0].x - tri[2].x, tri[0].y - tri[2].y);
    const double hs = 0.5 * (e0 + e1 + e2);
    S_.face_area += std::sqrt(std::max(0.0, hs * (hs - e0) * (hs - e1) * (hs - e2)));
    S_.bbox_area += (st.max_x - st.min_x) * (st.max_y - st.min_y);
  }

  // out = I + (1 - alpha)·background, alpha = 1 - T (premultiplied), where
  // the background is the opaque layer's colour in a mixed scene.
  // Untouched pixels (rgb 0, T 1) are the background exactly; touched ones
  // are computed, and their records reset for the next tile.
  void finish() {
    ws_.out.resize(npix_ * 4);
    const double* bg = rs_.background;
    float* const out = ws_.out.data();
    const uint32_t stride = under_ ? in_.under->stride() : 0;
    if (under_) {
      for (size_t p = 0; p < npix_; ++p)
        for (int k = 0; k < 4; ++k) out[p * 4 + k] = under_[p * stride + k];
    } else {
      const float b[4] = {float(bg[0]), float(bg[1]), float(bg[2]), float(bg[3])};
      for (size_t p = 0; p < npix_; ++p)
        for (int k = 0; k < 4; ++k) out[p * 4 + k] = b[k];
    }
    for (uint32_t p : ws_.touched) {
      PixelLight& l = ws_.light[p];
      const double T = l.T;
      float* o = &out[size_t(p) * 4];
      if (under_) {
        const float* u = under_ + size_t(p) * stride;
        for (int k = 0; k < 3; ++k) o[k] = float(l.rgb[k] + T * double(u[k]));
        o[3] = float((1.0 - T) + T * double(u[3]));
        S_.rays_stopped += std::isfinite(u[4]);
      } else {
        for (int k = 0; k < 3; ++k) o[k] = float(l.rgb[k] + T * bg[k]);
        o[3] = float((1.0 - T) + T * bg[3]);
      }
      if (T < 1.0) ++S_.rendered_pixels;
      ws_.px[p].reset();
      l.reset();
    }
    ws_.px_clean = true;
  }

  const SweepShared& in_;
  const RenderSettings& rs_;
  Viewport vp_;
  uint32_t vw_;
  TileWorkspace& ws_;
  RenderStats& S_;
  size_t npix_;  // this tile's pixels (the first npix_ records)
  PixelRecord* records_;
  const float* under_;  // the tile's opaque layer (mixed scenes), or null
  const float* clip_;
  Compositor comp_;
  bool timed_;
  uint64_t fragments_ = 0, max_len_ = 0;  // this tile's counts (kept out of S_ in the hot loop)
};

}  // namespace

void sweep_tile(const SweepShared& in, uint32_t tile, const Viewport& vp, uint64_t max_fragments, TileWorkspace& ws,
                RenderStats& stats) {
  TileSweep(in, tile, vp, max_fragments, ws, stats).run(tile);
}

}  // namespace zs
