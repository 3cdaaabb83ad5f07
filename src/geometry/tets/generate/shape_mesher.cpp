#include "geometry/tets/generate/shape_mesher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/tets/generate/shapes.h"
#include "geometry/tets/generate/tetgen_mesher.h"

namespace zs {

namespace {

// Surface edge length matching the mean tet volume V/N (a regular tet of
// volume v has edge 2.04 v^(1/3)).
double edge_for(double volume, double n) { return 2.0 * std::cbrt(volume / n); }

// One TetGen run: the surface resolution as for `ns` tets, the volume bound
// as for `nv`. Scaled together the count follows n whichever dominates;
// the surface alone moves in steps (whole numbers of segments), which the
// volume bound then fills in.
TetMesh run(const ShapeMeshOptions& opt, const ShapeInfo& info, double ns, double nv) {
  TetgenOptions to;
  to.quality = opt.quality;
  // -a bounds the largest tet, not the mean: 4 V/n lands near n.
  to.max_volume = 4.0 * info.volume / nv;
  to.preserve_surface = info.curved;
  to.max_tets = 0;  // the count is steered toward the target, itself bounded
  return tetrahedralize(make_shape(info.name, edge_for(info.volume, ns), opt.seed), to);
}


// Secant steps on log(count / target) over one log-scale knob, kept inside
// the bracket once the target is bracketed.
struct Steer {
  double lo = -INFINITY, hi = INFINITY;  // knob values known to give too few / too many
  double lo_f = NAN;                     // log(count / target) at lo
  double prev_x = NAN, prev_f = NAN;
  double next(double x, double f) {
    if (f > 0) {
      hi = std::min(hi, x);
    } else if (x > lo) {
      lo = x;
      lo_f = f;
    }
    double slope = 1.0;  // count ~ n
    if (std::isfinite(prev_x) && x != prev_x) slope = std::clamp((f - prev_f) / (x - prev_x), 0.2, 3.0);
    double n = x - f / slope;
    if (std::isfinite(lo) && std::isfinite(hi) && !(n > lo && n < hi)) n = (lo + hi) / 2;
    prev_x = x;
    prev_f = f;
    return n;
  }
};

}  // namespace

TetMesh mesh_shape(const ShapeMeshOptions& opt, ShapeMeshReport* report) {
  const ShapeInfo* info = find_shape(opt.shape);
  if (!info) throw std::invalid_argument("unknown shape '" + opt.shape + "'");
  if (opt.target_tets < 1) throw std::invalid_argument("target tet count must be positive");
  const double target = static_cast<double>(opt.target_tets);
  ShapeMeshReport rep;
  // Small runs cost milliseconds; a big target gets fewer reruns.
  const int max_runs = target <= 100000 ? 16 : 8;
  TetMesh best;
  double best_err = INFINITY;
  // Runs once at (xs, xv) = log of (ns, nv); returns the count.
  auto attempt = [&](double xs, double xv) {
    TetMesh m = run(opt, *info, std::exp(xs), std::exp(xv));
    ++rep.runs;
    const double count = static_cast<double>(m.num_tets());
    if (std::abs(count / target - 1) < best_err) {
      best_err = std::abs(count / target - 1);
      best = std::move(m);
    }
    return count;
  };

  // Big targets start from a cheap calibration run (count / n at 15,000
  // carries over well).
  double x = std::log(target);
  const double small = 15000;
  if (target > 3 * small) x -= std::log(attempt(std::log(small), std::log(small)) / small);
  // 1. Surface and volume bound together.
  Steer joint;
  while (rep.runs < max_runs / 2 && best_err > opt.tolerance) {
    const double f = std::log(attempt(x, x) / target);
    if (best_err <= opt.tolerance) break;
    x = joint.next(x, f);
  }
  // 2. The target fell between two surface resolutions: keep the coarser
  // one (too few tets) and tighten the volume bound alone.
  if (best_err > opt.tolerance && std::isfinite(joint.lo)) {
    const double xs = joint.lo;
    Steer vol;
    vol.lo = vol.prev_x = xs;
    vol.lo_f = vol.prev_f = joint.lo_f;
    double xv = xs - joint.lo_f;  // count ~ nv to start with
    while (rep.runs < max_runs && best_err > opt.tolerance)
      xv = vol.next(xv, std::log(attempt(xs, xv) / target));
  }
  // Never below the target, however coarse the request: the shape's fixed
  // features take more tets than that at this quality bound.
  rep.at_floor = best_err > opt.tolerance && !std::isfinite(joint.lo) && best.num_tets() > opt.target_tets;
  rep.tets = best.num_tets();
  rep.target = opt.target_tets;
  if (report) *report = rep;
  return best;
}

}  // namespace zs
