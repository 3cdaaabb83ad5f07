#include "render/reference/reference_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "render/reference/boundary_hits.h"
#include "render/reference/tet_walk.h"
#include "base/view/camera.h"
#include "base/util/bytes_str.h"
#include "base/optics/segment_integrator.h"
#include "base/util/memory.h"

namespace zs {

namespace {

struct RowCounters {
  uint64_t rays_hit = 0, segments = 0, tet_steps = 0, entries = 0, lost = 0, clipped = 0, stopped = 0;
};

}  // namespace

Image render_reference(const TetMesh& mesh, const Topology& topo, const FrameSettings& rs, const TransferFunction& tf,
                       ReferenceStats* stats, const ReferenceUnder* under) {
  std::vector<uint32_t> rows(rs.height);
  for (uint32_t j = 0; j < rs.height; ++j) rows[j] = j;
  return render_reference_rows(mesh, topo, rs, tf, rows, stats, under);
}

Image render_reference_rows(const TetMesh& mesh, const Topology& topo, const FrameSettings& rs,
                            const TransferFunction& tf, const std::vector<uint32_t>& rows_wanted, ReferenceStats* stats,
                            const ReferenceUnder* under) {
  const auto t_start = std::chrono::steady_clock::now();
  // The reference keeps its rows in memory: refuse what the budget cannot
  // hold before allocating it.
  if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");
  const uint64_t budget = rs.budget();
  const uint64_t image_bytes = uint64_t(rs.width) * rows_wanted.size() * 16;
  if (image_bytes >= budget)
    throw std::runtime_error("memory budget of " + bytes_str(budget) + " cannot hold the reference's " +
                             std::to_string(rs.width) + "x" + std::to_string(rows_wanted.size()) + " float image (" +
                             bytes_str(image_bytes) + ")");
  const View view(rs.camera, rs.width, rs.height);
  const SolidFaces solid = build_solid_faces(mesh, topo);
  const BoundaryBins bins(mesh, topo, solid, view);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  if (mesh.scalars.size() != mesh.points.size() && mesh.cell_scalars.size() != mesh.tets.size())
    throw std::invalid_argument("reference: mesh has no point or cell scalars");
  Image img(rs.width, uint32_t(rows_wanted.size()));
  // Lengths below this are rounding, not geometry (a seam's exit and entry).
  const double eps = 1e-10 * std::max(bounds_of(mesh).diagonal(), 1e-300);

  tbb::enumerable_thread_specific<RowCounters> counters;
  tbb::enumerable_thread_specific<std::vector<BoundaryHit>> hit_buffers;
  auto do_rows = [&](const tbb::blocked_range<uint32_t>& rows) {
    RowCounters& c = counters.local();
    std::vector<BoundaryHit>& hits = hit_buffers.local();
    for (uint32_t row = rows.begin(); row < rows.end(); ++row)
      for (uint32_t i = 0; i < rs.width; ++i) {
        const uint32_t j = rows_wanted[row];
        glm::dvec3 o, d;
        view.ray(double(i), double(j), &o, &d);
        bins.hits(i, j, o, d, &hits);
        // The part of the ray the clip planes keep (everything: ±inf).
        double t_lo, t_hi;
        if (!rs.clip.interval(o, d, &t_lo, &t_hi)) hits.clear();
        // Opaque geometry: the ray stops at its view depth (ray length = depth · factor).
        const size_t pix = size_t(j) * rs.width + i;
        const float zu = under ? under->z[pix] : INFINITY;
        if (std::isfinite(zu)) t_hi = std::min(t_hi, double(zu) * view.ray_length_factor(double(i), double(j)));
        double rgb[3] = {0, 0, 0}, T = 1.0;
        double t_done = -INFINITY;  // the line is integrated (or walked) up to here
        bool hit = false;
        for (const BoundaryHit& h : hits) {
          // Entries behind the end of the last walk were crossed by it (a
          // second face of a shared edge, say); a seam's coincident entry sits
          // within rounding of it and is taken.
          if (!h.entry || h.t < t_done - eps - 1e-12 * std::abs(h.t)) continue;
          ++c.entries;
          const WalkResult w = walk_line(mesh, topo, solid, o, d, h.face, h.t, [&](const WalkSegment& s) {
            const double a = std::max({s.t0, t_done, 0.0, t_lo}), b = std::min(s.t1, t_hi);
            if (!(b > a)) {
              c.clipped += s.t1 > s.t0 && (s.t1 <= t_lo || s.t0 >= t_hi);
              return;
            }
            c.clipped += a == t_lo || b == t_hi;
            // A cell with a non-finite scalar is empty (the engine drops it too).
            if (!std::isfinite(s.s0) || !std::isfinite(s.s1)) return;
            // Scalars at the cut ends, linear in t within the tet.
            const double s0 = s.t1 > s.t0 ? s.s0 + (s.s1 - s.s0) * (a - s.t0) / (s.t1 - s.t0) : s.s0;
            const double s1 = b == s.t1 ? s.s1 : s.s0 + (s.s1 - s.s0) * (b - s.t0) / (s.t1 - s.t0);
            const SegmentLight l = integ.integrate(s0, s1, b - a);
            for (int k = 0; k < 3; ++k) rgb[k] += T * l.rgb[k];
            T *= l.T;
            ++c.segments;
            hit = true;
          });
          c.tet_steps += w.steps;
          c.lost += w.lost;
          t_done = std::max(t_done, w.t_exit);
        }
        c.rays_hit += hit;
        c.stopped += hit && std::isfinite(zu);
        float* out = img.at(i, row);
        double bg[4] = {rs.background[0], rs.background[1], rs.background[2], rs.background[3]};
        if (under)
          for (int k = 0; k < 4; ++k) bg[k] = under->rgba->rgba[pix * 4 + size_t(k)];
        for (int k = 0; k < 3; ++k) out[k] = float(rgb[k] + T * bg[k]);
        out[3] = float((1.0 - T) + T * bg[3]);
      }
  };
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(std::max(1, rs.threads)));
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(rows_wanted.size()), 1), do_rows);
  }
  if (stats) {
    *stats = ReferenceStats{};
    for (const RowCounters& c : counters) {
      stats->rays_hit += c.rays_hit;
      stats->segments += c.segments;
      stats->tet_steps += c.tet_steps;
      stats->entries += c.entries;
      stats->lost_walks += c.lost;
      stats->segments_clipped += c.clipped;
      stats->rays_stopped += c.stopped;
    }
    stats->boundary_faces = bins.num_faces();
    for (uint8_t f : solid.flat) stats->flat_tets += f;
    stats->unbinned_faces = bins.everywhere_faces();
    stats->ms_total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start).count();
  }
  return img;
}

}  // namespace zs
