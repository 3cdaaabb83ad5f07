#include "render/volume/face_classes.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

namespace zs {

namespace {
constexpr size_t kGrain = 1 << 14;
}

std::vector<FaceClass> classify_faces(const TetMesh& m, const Topology& topo, const TransferFunction& tf,
                                      const View& view, FaceClassCounts* counts,
                                      std::vector<uint8_t>* tet_visible, std::vector<uint8_t>* on_visible,
                                      std::vector<FaceClass> storage, const ClipRegion* clip) {
  if (clip && clip->empty()) clip = nullptr;
  const size_t nt = m.num_tets();
  const bool cell = m.has_cell_scalars();
  std::vector<uint8_t> visible(nt, 0);
  if (on_visible) on_visible->assign(m.num_points(), 0);
  tbb::combinable<FaceClassCounts> part;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    FaceClassCounts& c = part.local();
    for (size_t t = r.begin(); t < r.end(); ++t) {
      if (topo.tet_degenerate[t]) {
        ++c.tets_degenerate;
        continue;
      }
      if (clip) {
        const Tet& tv = m.tets[t];
        const glm::dvec3 p[4] = {m.points[tv[0]], m.points[tv[1]], m.points[tv[2]], m.points[tv[3]]};
        if (clip->excludes(p, 4)) {
          ++c.tets_clipped;
          continue;
        }
      }
      // The scalar range over the tet: its own value (cell data), else its
      // vertices' (no scalars: 0).
      double lo = INFINITY, hi = -INFINITY;
      if (cell) {
        lo = hi = m.cell_scalars[t];
      } else {
        for (uint32_t v : m.tets[t]) {
          const double s = m.has_scalars() ? m.scalars[v] : 0.0;
          lo = std::min(lo, s);
          hi = std::max(hi, s);
        }
      }
      if (tf.transparent_over(lo, hi)) {
        ++c.tets_invisible;
        continue;
      }
      visible[t] = 1;
      c.cell_data_tets += cell;
      if (on_visible)
        for (uint32_t v : m.tets[t]) std::atomic_ref<uint8_t>((*on_visible)[v]).store(1, std::memory_order_relaxed);
    }
  });

  std::vector<FaceClass> cls = std::move(storage);  // a previous frame's, when given
  cls.assign(topo.num_faces(), FaceClass::Culled);
  const glm::dvec3 eye = view.eye(), fwd = view.forward();
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(topo.num_faces()), kGrain),
                    [&](const tbb::blocked_range<uint32_t>& r) {
    FaceClassCounts& c = part.local();
    for (uint32_t f = r.begin(); f < r.end(); ++f) {
      const uint32_t t0 = topo.tet0(f), t1 = topo.tet1(f);
      const bool v0 = visible[t0] != 0;
      const bool v1 = t1 != kNoTet && visible[t1] != 0;
      if (!v0 && !v1) {
        ++c.faces_culled;
        continue;
      }
      // Whether rays cross face f into tet t: they come from the eye's side of
      // the face's plane (the eye itself, or against the view direction
      // when orthographic) and enter t iff t lies on the other side.
      auto entered = [&](uint32_t t) {
        const auto fv = topo.face(f);
        uint32_t opp = m.tets[t][0];
        for (uint32_t v : m.tets[t])
          if (v != fv[0] && v != fv[1] && v != fv[2]) opp = v;
        const glm::dvec3 a = m.points[fv[0]];
        const glm::dvec3 n = glm::cross(m.points[fv[1]] - a, m.points[fv[2]] - a);
        const double side_tet = glm::dot(n, m.points[opp] - a);
        const double side_eye = view.perspective() ? glm::dot(n, eye - a) : -glm::dot(n, fwd);
        return (side_tet > 0) != (side_eye > 0);
      };
      if (v0 && v1) {
        // Cell data: the value behind the face is tet1's when rays leave tet0 here.
        cls[f] = cell && !entered(t0) ? FaceClass(uint8_t(FaceClass::Interior) | kValueTet1) : FaceClass::Interior;
        continue;
      }
      // One visible side: entry iff the rays enter that tet.
      const uint32_t t = v0 ? t0 : t1;
      const FaceClass k = entered(t) ? FaceClass::Entry : FaceClass::Exit;
      cls[f] = cell && t == t1 ? FaceClass(uint8_t(k) | kValueTet1) : k;
    }
  });
  part.combine_each([&](const FaceClassCounts& c) {
    counts->tets_invisible += c.tets_invisible;
    counts->tets_degenerate += c.tets_degenerate;
    counts->faces_culled += c.faces_culled;
    counts->cell_data_tets += c.cell_data_tets;
    counts->tets_clipped += c.tets_clipped;
  });
  if (tet_visible) *tet_visible = std::move(visible);
  return cls;
}

}  // namespace zs
