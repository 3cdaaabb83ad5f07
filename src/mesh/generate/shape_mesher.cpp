#include "mesh/generate/shape_mesher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mesh/generate/shapes.h"
#include "mesh/generate/tetgen_mesher.h"

namespace zs {

namespace {

// Surface edge length matching the mean tet volume V/N (a regular tet of
// volume v has edge 2.04 v^(1/3)).
double edge_for(double volume, double n) { return 2.0 * std::cbrt(volume / n); }

TetMesh run(const ShapeMeshOptions& opt, const ShapeInfo& info, double n, double c) {
  TetgenOptions to;
  to.quality = opt.quality;
  to.max_volume = c * info.volume / n;
  to.preserve_surface = info.curved;
  to.max_tets = 0;  // the count is steered toward --tets, itself bounded
  return tetrahedralize(make_shape(info.name, edge_for(info.volume, n), opt.seed), to);
}

}  // namespace

TetMesh mesh_shape(const ShapeMeshOptions& opt) {
  const ShapeInfo* info = find_shape(opt.shape);
  if (!info) throw std::invalid_argument("unknown shape '" + opt.shape + "'");
  if (opt.target_tets < 1) throw std::invalid_argument("target tet count must be positive");
  const double target = static_cast<double>(opt.target_tets);

  // max_volume = c * V / N; c > 1 because -a bounds the largest tet, not the mean.
  double c = 4.0;
  const double small = 15000;
  if (target > 3 * small) {
    for (int i = 0; i < 2; ++i) {
      double n = static_cast<double>(run(opt, *info, small, c).num_tets());
      c *= n / small;
      if (std::abs(n / small - 1) < 0.1) break;
    }
  }
  TetMesh best;
  double best_err = INFINITY;
  for (int i = 0; i < 4; ++i) {
    TetMesh m = run(opt, *info, target, c);
    double n = static_cast<double>(m.num_tets());
    double err = std::abs(n / target - 1);
    if (err < best_err) {
      best_err = err;
      best = std::move(m);
    }
    if (err <= opt.tolerance) break;
    // Damp the correction a little: the surface share does not scale with c.
    c *= std::pow(n / target, 0.9);
  }
  return best;
}

}  // namespace zs
