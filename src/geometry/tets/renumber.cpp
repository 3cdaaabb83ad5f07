#include "geometry/tets/renumber.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace zs {

namespace {

// Spreads the low 21 bits of x to every third bit.
uint64_t spread3(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

constexpr size_t kGrain = 1 << 14;

}  // namespace

uint64_t morton_code(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  uint64_t q[3];
  for (int a = 0; a < 3; ++a) {
    const double span = hi[a] - lo[a];
    const double t = span > 0 ? (p[a] - lo[a]) / span : 0.0;
    q[a] = uint64_t(std::clamp(t, 0.0, 1.0) * double((1 << 21) - 1));
  }
  return spread3(q[0]) | spread3(q[1]) << 1 | spread3(q[2]) << 2;
}

double id_spread(const TetMesh& m) {
  if (m.tets.empty() || m.points.empty()) return 0;
  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, m.tets.size(), kGrain), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double s) {
        for (size_t t = r.begin(); t < r.end(); ++t) {
          const Tet& x = m.tets[t];
          s += double(std::max({x[0], x[1], x[2], x[3]}) - std::min({x[0], x[1], x[2], x[3]}));
        }
        return s;
      },
      std::plus<double>());
  return sum / double(m.tets.size()) / std::cbrt(double(m.points.size()) * double(m.points.size()));
}

RenumberStats renumber_for_locality(TetMesh& m) {
  RenumberStats st;
  const size_t nv = m.points.size(), nt = m.tets.size();
  st.spread_before = id_spread(m);
  if (nv == 0) return st;
  // Points: sorted by (code, old id); non-finite points get the largest code.
  const Bounds b = bounds_of(m);
  std::vector<unsigned __int128> key(nv);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v < r.end(); ++v) {
      const glm::dvec3& p = m.points[v];
      const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      const uint64_t code = finite && !b.empty ? morton_code(p, b.lo, b.hi) : UINT64_MAX;
      key[v] = (unsigned __int128)code << 32 | v;
    }
  });
  tbb::parallel_sort(key.begin(), key.end());
  std::vector<uint32_t> new_id(nv);
  {
    std::vector<glm::dvec3> points(nv);
    std::vector<double> scalars(m.scalars.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, kGrain), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) {
        const uint32_t old = uint32_t(key[i]);
        new_id[old] = uint32_t(i);
        points[i] = m.points[old];
        if (!scalars.empty()) scalars[i] = m.scalars[old];
      }
    });
    std::vector<unsigned __int128>().swap(key);
    m.points.swap(points);
    m.scalars.swap(scalars);
  }
  // Tets: renamed in place, then ordered by their smallest new point id (a
  // stable counting sort: tets of one point keep their order).
  std::vector<uint32_t> start(nv + 1, 0);
  for (Tet& t : m.tets) {
    for (uint32_t& v : t) v = v < nv ? new_id[v] : v;  // out-of-range ids stay out of range
    ++start[std::min<size_t>(std::min({t[0], t[1], t[2], t[3]}), nv - 1) + 1];
  }
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<Tet> tets(nt);
  std::vector<double> cell(m.cell_scalars.size());  // cell data move with their tets
  for (size_t i = 0; i < nt; ++i) {
    const Tet& t = m.tets[i];
    const size_t to = start[std::min<size_t>(std::min({t[0], t[1], t[2], t[3]}), nv - 1)]++;
    tets[to] = t;
    if (!cell.empty()) cell[to] = m.cell_scalars[i];
  }
  m.tets.swap(tets);
  m.cell_scalars.swap(cell);
  st.spread_after = id_spread(m);
  st.renumbered = true;
  char note[160];
  std::snprintf(note, sizeof note, "points and tets renumbered along a Morton curve for locality (id spread %.1f -> %.1f)",
                st.spread_before, st.spread_after);
  m.notes.push_back(note);
  return st;
}

}  // namespace zs
