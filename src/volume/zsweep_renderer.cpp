#include "volume/zsweep_renderer.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <string>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "raster/bbox_scan.h"
#include "raster/bconvert_scan.h"
#include "raster/span_scan.h"
#include "raster/screen_triangle.h"
#include "util/progress.h"
#include "volume/compositor.h"
#include "volume/face_classes.h"
#include "volume/near_clip.h"
#include "volume/pixel_lists.h"
#include "volume/vertex_heap.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::string bytes_str(uint64_t b) {
  char buf[64];
  if (b >= (uint64_t(1) << 20)) std::snprintf(buf, sizeof buf, "%.1f MiB", double(b) / 1048576.0);
  else std::snprintf(buf, sizeof buf, "%llu bytes", (unsigned long long)b);
  return buf;
}

// Everything the tiles share, computed once: mesh -> view.
struct SweepInput {
  const Topology& topo;
  const RenderSettings& rs;
  const View& view;
  std::vector<ScreenVertex> sv;            // every vertex in view space
  std::vector<FaceClass> cls;              // per face
  std::vector<VertexHeap::Entry> events;   // vertices that start a face to project
  std::vector<NearTriangle> near;          // clipped faces and cross-sections at z_near
  std::vector<uint8_t> clipped;            // per face: replaced by its near triangles
  double z_origin = 0;                     // fragments store depth - z_origin
};

void add_stats(RenderStats& a, const RenderStats& b) {
  a.ms_list_generation += b.ms_list_generation;
  a.ms_scan_convert += b.ms_scan_convert;
  a.ms_insert += b.ms_insert;
  a.ms_composite += b.ms_composite;
  a.pixel_tests += b.pixel_tests;
  a.pixel_hits += b.pixel_hits;
  a.pixel_misses += b.pixel_misses;
  a.fragments += b.fragments;
  a.faces_projected += b.faces_projected;
  a.faces_offscreen += b.faces_offscreen;
  a.faces_degenerate += b.faces_degenerate;
  a.max_list_length = std::max(a.max_list_length, b.max_list_length);
  a.forced_composites += b.forced_composites;
  a.budget_flushes += b.budget_flushes;
  a.composite_events += b.composite_events;
  a.segments += b.segments;
  a.early_terminated_pixels += b.early_terminated_pixels;
  a.peak_fragments = std::max(a.peak_fragments, b.peak_fragments);  // per band
  a.bconvert_fallbacks += b.bconvert_fallbacks;
  for (int k = 0; k < 4; ++k) a.row_end_misses[k] += b.row_end_misses[k];
  a.face_area += b.face_area;
  a.bbox_area += b.bbox_area;
}

// One sweep over the whole mesh for the pixels of `vp` (digest §1.2).
void sweep_tile(const SweepInput& in, const Viewport& vp, uint64_t max_fragments, const SegmentIntegrator& integ,
                std::vector<float>& band, RenderStats& S, Progress& progress) {
  const Topology& topo = in.topo;
  const RenderSettings& rs = in.rs;
  const View& view = in.view;
  const auto& sv = in.sv;
  const auto& cls = in.cls;
  const uint32_t vw = uint32_t(vp.x1 - vp.x0), vh = uint32_t(vp.y1 - vp.y0);
  const uint32_t npix = vw * vh;

  VertexHeap heap;
  heap.assign(in.events);
  std::vector<uint8_t> projected = in.clipped;  // clipped faces are drawn as near pieces
  const double et = rs.early_termination > 0 ? rs.early_termination / 510.0 : 0.0;
  Compositor comp(view, vp, integ, et);
  PixelLists lists(npix, max_fragments);

  auto composite_all = [&](float z_limit) {
    const auto t0 = Clock::now();
    for (uint32_t p : lists.active()) comp.composite(lists, p, z_limit);
    lists.compact_active();
    S.ms_composite += ms_since(t0);
  };

  FaceFragments frags;
  BConvertScratch bscratch;
  // Scan-converts one triangle and inserts its fragments (z_sweep: the depth
  // before which every fragment is final, for forced compositing).
  auto project = [&](const ScreenVertex tri[3], FaceClass fclass, float z_sweep) {
    const double min_x = std::min({tri[0].x, tri[1].x, tri[2].x}), max_x = std::max({tri[0].x, tri[1].x, tri[2].x});
    const double min_y = std::min({tri[0].y, tri[1].y, tri[2].y}), max_y = std::max({tri[0].y, tri[1].y, tri[2].y});
    if (max_x < vp.x0 - 0.5 || min_x > vp.x1 - 0.5 || max_y < vp.y0 - 0.5 || min_y > vp.y1 - 0.5) {
      ++S.faces_offscreen;
      return;
    }
    // list_generation: per-face set-up (plane equations; B-Convert's edge
    // and compact lists); scan_convert: the pixel loop.
    const auto t0 = Clock::now();
    ScreenTriangle st;
    const bool ok = setup_triangle(tri, view.perspective(), &st);
    bool use_bconvert = ok && rs.scan == ScanStrategy::BConvert;
    if (use_bconvert && !bconvert_list(tri, rs.bconvert_variant, vp, bscratch)) {
      use_bconvert = false;
      ++S.bconvert_fallbacks;
    }
    const auto t1 = Clock::now();
    S.ms_list_generation += std::chrono::duration<double, std::milli>(t1 - t0).count();
    if (!ok) {
      ++S.faces_degenerate;
      return;
    }
    ++S.faces_projected;
    // Heron's formula on the screen edges (Eqs. 4.1-4.3) and the box area,
    // for the face / bounding-box ratio of Table 4.4.
    if (rs.face_area_stats) {
      const double e0 = std::hypot(tri[1].x - tri[0].x, tri[1].y - tri[0].y);
      const double e1 = std::hypot(tri[2].x - tri[1].x, tri[2].y - tri[1].y);
      const double e2 = std::hypot(tri[0].x - tri[2].x, tri[0].y - tri[2].y);
      const double hs = 0.5 * (e0 + e1 + e2);
      S.face_area += std::sqrt(std::max(0.0, hs * (hs - e0) * (hs - e1) * (hs - e2)));
      S.bbox_area += (st.max_x - st.min_x) * (st.max_y - st.min_y);
    }
    frags.clear();
    ScanCounters sc;
    if (use_bconvert) {
      RowEndMisses re;
      bconvert_scan(st, vp, bscratch, frags, sc, &re);
      for (int k = 0; k < 4; ++k) S.row_end_misses[k] += re.count[k];
    } else if (rs.scan == ScanStrategy::Span) {
      scan_span(st, vp, frags, sc);
    } else {
      scan_bbox(st, vp, frags, sc);
    }
    S.pixel_tests += sc.pixel_tests;
    S.pixel_hits += sc.pixel_hits;
    S.pixel_misses += sc.pixel_misses;
    auto t2 = Clock::now();
    S.ms_scan_convert += std::chrono::duration<double, std::milli>(t2 - t1).count();
    if (rs.raster_only) return;

    const uint32_t kind = fclass == FaceClass::Entry ? kEntry : fclass == FaceClass::Exit ? kExit : kInterior;
    for (size_t k = 0; k < frags.size(); ++k) {
      const uint32_t p = uint32_t(frags.y[k] - vp.y0) * vw + uint32_t(frags.x[k] - vp.x0);
      if (comp.done(p)) continue;  // early-terminated: nothing behind matters
      const float z = float(frags.z[k] - in.z_origin), s = float(frags.s[k]);
      if (!lists.insert(p, z, s, kind)) {
        // Pool at its budget: composite everything already final (before
        // the sweep plane) everywhere, then retry once.
        ++S.budget_flushes;
        S.ms_insert += ms_since(t2);
        composite_all(z_sweep);
        t2 = Clock::now();
        if (!lists.insert(p, z, s, kind))
          throw std::runtime_error("memory budget too small: " + std::to_string(lists.live_fragments()) +
                                   " fragments (" + bytes_str(lists.live_fragments() * sizeof(Fragment)) +
                                   ") must be pending at once in this view");
      }
      ++S.fragments;
      const uint32_t len = lists.length(p);
      if (len > S.max_list_length) S.max_list_length = len;
      if (rs.max_list_length && len > rs.max_list_length) {
        ++S.forced_composites;  // force this pixel's final fragments out now
        comp.composite(lists, p, z_sweep);
      }
    }
    S.ms_insert += ms_since(t2);
  };

  // Near-plane pieces first: they start at z_near, before every vertex.
  for (const NearTriangle& nt : in.near) project(nt.v, nt.cls, -INFINITY);
  double z_target = -INFINITY;
  uint64_t popped = 0;
  while (!heap.empty()) {
    const VertexHeap::Entry ev = heap.pop();
    if ((++popped & 4095) == 0) progress.add(4096);
    const float z_sweep = float(ev.z - in.z_origin);
    if (ev.z > z_target) {
      // The sweep passed z_target: every face still to come starts at or
      // after ev.z, so every fragment before ev.z is final. Composite them
      // and aim at the farthest vertex of this vertex's faces (ZSweep's
      // z_target), so compositing stays delayed but lists stay short.
      if (!lists.active().empty()) {
        ++S.composite_events;
        composite_all(z_sweep);
      }
      z_target = ev.z;
      for (uint32_t f : topo.use_set(ev.v))
        for (uint32_t v : topo.faces[f]) z_target = std::max(z_target, sv[v].z);
    }
    for (uint32_t f : topo.use_set(ev.v)) {
      if (projected[f] || cls[f] == FaceClass::Culled) continue;
      projected[f] = 1;
      const auto& fv = topo.faces[f];
      const ScreenVertex tri[3] = {sv[fv[0]], sv[fv[1]], sv[fv[2]]};
      project(tri, cls[f], z_sweep);
    }
  }
  progress.add(popped & 4095);
  composite_all(INFINITY);
  S.segments += comp.segments();
  S.early_terminated_pixels += comp.terminated_pixels();
  S.peak_fragments += lists.peak_fragments();

  // out = I + (1 - alpha)·background, alpha = 1 - T (premultiplied).
  band.resize(size_t(npix) * 4);
  for (uint32_t p = 0; p < npix; ++p) {
    const double T = comp.transmittance(p);
    const double* c = comp.rgb(p);
    float* o = &band[size_t(p) * 4];
    for (int k = 0; k < 3; ++k) o[k] = float(c[k] + T * rs.background[k]);
    o[3] = float((1.0 - T) + T * rs.background[3]);
    if (T < 1.0) ++S.rendered_pixels;
  }
}

}  // namespace

uint64_t default_memory_budget() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? uint64_t(pages) * uint64_t(size) / 2 : (uint64_t(4) << 30);
}

uint64_t zsweep_shared_bytes(size_t num_points, size_t num_faces) {
  const uint64_t per_point = sizeof(ScreenVertex) + 2 * sizeof(VertexHeap::Entry);
  return num_points * per_point + num_faces * 2 /*class, clipped*/;
}

BandPlan plan_bands(uint64_t budget, size_t num_points, size_t num_faces, uint32_t width, uint32_t height,
                    int threads, uint64_t sink_bytes) {
  threads = std::max(1, threads);
  const uint64_t shared = zsweep_shared_bytes(num_points, num_faces) + sink_bytes +
                          uint64_t(threads) * num_faces /*projected flags*/;
  const uint64_t row_bytes = kBytesPerPixel * width;
  if (shared + uint64_t(threads) * 2 * row_bytes >= budget)
    throw std::runtime_error("memory budget of " + bytes_str(budget) + " cannot hold a " + std::to_string(width) +
                             "x" + std::to_string(height) + " render of this mesh (needs more than " +
                             bytes_str(shared + uint64_t(threads) * 2 * row_bytes) + ")");
  const uint64_t per_band_state = (budget - shared) / 2 / uint64_t(threads);
  // Several bands per thread balance uneven bands; more when one band's pixel
  // state would not fit. Per-pixel results do not depend on the banding.
  BandPlan p;
  p.bands = threads == 1 ? 1 : std::min<uint64_t>(height, uint64_t(4) * threads);
  const uint64_t rows_fit = std::max<uint64_t>(1, per_band_state / row_bytes);
  p.bands = std::max(p.bands, (uint64_t(height) + rows_fit - 1) / rows_fit);
  p.band_rows = (uint64_t(height) + p.bands - 1) / p.bands;
  p.bands = (uint64_t(height) + p.band_rows - 1) / p.band_rows;
  p.max_fragments = (budget - shared - uint64_t(threads) * p.band_rows * row_bytes) / sizeof(Fragment) / uint64_t(threads);
  return p;
}

uint64_t peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return uint64_t(u.ru_maxrss) * 1024;
}

void render_zsweep_bands(const TetMesh& mesh, const Topology& topo, const RenderSettings& rs, BandSink& sink,
                         uint64_t sink_bytes, RenderStats* st) {
  const auto t_start = Clock::now();
  RenderStats local;
  RenderStats& S = st ? *st : local;
  S = RenderStats{};
  if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");

  const View view(rs.camera, rs.width, rs.height);
  const int threads = std::max(1, rs.threads);
  const uint64_t budget = rs.memory_budget_bytes ? rs.memory_budget_bytes : default_memory_budget();
  S.memory_budget_bytes = budget;
  const BandPlan plan = plan_bands(budget, mesh.num_points(), topo.num_faces(), rs.width, rs.height, threads, sink_bytes);
  const uint64_t bands = plan.bands, band_rows = plan.band_rows, max_fragments = plan.max_fragments;
  S.bands = bands;
  S.fragment_capacity = max_fragments;

  SweepInput in{topo, rs, view, {}, {}, {}, {}, {}, 0};
  in.sv.resize(mesh.num_points());
  double zmin = INFINITY;
  for (uint32_t v = 0; v < mesh.num_points(); ++v) {
    const ViewPoint p = view.project(mesh.points[v]);
    in.sv[v] = {p.x, p.y, p.z, mesh.has_scalars() ? mesh.scalars[v] : 0.0, v};
    if (p.z > 0) zmin = std::min(zmin, p.z);
  }
  // Fragments store depth relative to the nearest vertex, as float: keeps
  // their precision when the camera is far from the mesh.
  in.z_origin = std::isfinite(zmin) ? zmin : 0.0;

  // Perspective rays start at the eye: keep a tiny positive near distance so
  // that projecting never divides by zero. Orthographic rays start on the eye plane.
  const double z_near = view.perspective() ? 1e-7 * std::max(bounds_of(mesh).diagonal(), 1e-300) : 0.0;
  FaceClassCounts fc;
  std::vector<uint8_t> tet_visible;
  in.cls = classify_faces(mesh, topo, rs.tf, view, &fc, &tet_visible);
  in.clipped.assign(topo.num_faces(), 0);
  if (std::any_of(in.sv.begin(), in.sv.end(), [&](const ScreenVertex& v) { return !(v.z > z_near); }))
    clip_at_near_plane(mesh, topo, view, in.sv, in.cls, tet_visible, z_near, &in.near, &in.clipped);
  S.faces_clipped = uint64_t(std::count(in.clipped.begin(), in.clipped.end(), 1));
  S.tets_invisible = fc.tets_invisible;
  S.tets_degenerate = fc.tets_degenerate;
  S.faces_culled = fc.faces_culled;
  for (uint32_t v = 0; v < mesh.num_points(); ++v) {
    if (!(in.sv[v].z > z_near) || !std::isfinite(in.sv[v].z)) continue;
    for (uint32_t f : topo.use_set(v))
      if (in.cls[f] != FaceClass::Culled) {
        in.events.push_back({in.sv[v].z, v});
        break;
      }
  }
  const SegmentIntegrator integ(rs.tf, rs.integrator);
  S.ms_setup = ms_since(t_start);

  Progress progress("render", uint64_t(in.events.size()) * bands, rs.progress);
  std::vector<RenderStats> tile_stats(bands);
  std::mutex sink_mu;
  auto run_band = [&](uint64_t b) {
    const int y0 = int(std::min<uint64_t>(rs.height, b * band_rows));
    const int y1 = int(std::min<uint64_t>(rs.height, (b + 1) * band_rows));
    if (y0 >= y1) return;
    std::vector<float> buf;
    sweep_tile(in, Viewport{0, y0, int(rs.width), y1}, max_fragments, integ, buf, tile_stats[b], progress);
    std::lock_guard<std::mutex> lock(sink_mu);
    sink.band(uint32_t(y0), uint32_t(y1), buf.data());
  };
  if (bands == 1 || threads == 1) {
    for (uint64_t b = 0; b < bands; ++b) run_band(b);
  } else {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    tbb::parallel_for(uint64_t(0), bands, run_band);
  }
  progress.finish();
  for (const RenderStats& t : tile_stats) {
    add_stats(S, t);
    S.rendered_pixels += t.rendered_pixels;
  }
  S.peak_rss_bytes = peak_rss_bytes();
  S.ms_total = ms_since(t_start);
}

Image render_zsweep(const TetMesh& mesh, const Topology& topo, const RenderSettings& rs, RenderStats* st) {
  struct ImageSink : BandSink {
    Image img;
    void band(uint32_t y0, uint32_t y1, const float* rgba) override {
      std::copy(rgba, rgba + size_t(y1 - y0) * img.width * 4, img.at(0, y0));
    }
  } sink;
  if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");
  const uint64_t image_bytes = uint64_t(rs.width) * rs.height * 16;
  const uint64_t budget = rs.memory_budget_bytes ? rs.memory_budget_bytes : default_memory_budget();
  if (image_bytes >= budget)
    throw std::runtime_error("memory budget of " + bytes_str(budget) + " cannot hold a " + std::to_string(rs.width) +
                             "x" + std::to_string(rs.height) + " float image (" + bytes_str(image_bytes) + ")");
  sink.img = Image(rs.width, rs.height);
  render_zsweep_bands(mesh, topo, rs, sink, image_bytes, st);
  return std::move(sink.img);
}

}  // namespace zs
