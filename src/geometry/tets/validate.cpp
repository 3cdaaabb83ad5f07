#include "geometry/tets/validate.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace zs {

namespace {

bool finite3(const glm::dvec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// canon[v] = the lowest-index point with exactly v's coordinates. Exact
// equality: merging within a tolerance is a reader's decision, not ours.
std::vector<uint32_t> canonical_points(const TetMesh& m, size_t* duplicates) {
  const size_t n = m.points.size();
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  auto less = [&](uint32_t a, uint32_t b) {
    const auto &p = m.points[a], &q = m.points[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<uint32_t> canon(n);
  *duplicates = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t v = order[i];
    if (i > 0 && finite3(m.points[v]) && m.points[v] == m.points[order[i - 1]]) {
      canon[v] = canon[order[i - 1]];
      ++*duplicates;
    } else {
      canon[v] = v;
    }
  }
  return canon;
}

// Boundary faces that fold back onto a neighbouring boundary face: they share
// an edge, lie in (nearly) the same plane, and their third vertices are on the
// same side of that edge, so the two overlap. A closed surface never does this;
// a seam that was not stitched (boundary on both sides, same place) does.
size_t count_coincident_boundary(const TetMesh& m, const Topology& topo,
                                 const std::vector<uint32_t>& canon) {
  struct EdgeRec {
    uint32_t a, b, face;
  };
  std::vector<EdgeRec> edges;
  edges.reserve(3 * topo.num_boundary_faces);
  for (uint32_t f = 0; f < topo.num_faces(); ++f) {
    if (!topo.is_boundary(f)) continue;
    const auto v = topo.face(f);
    for (int k = 0; k < 3; ++k) {
      uint32_t a = canon[v[k]], b = canon[v[(k + 1) % 3]];
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      edges.push_back({a, b, f});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const EdgeRec& x, const EdgeRec& y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.face < y.face);
  });
  auto third = [&](uint32_t f, uint32_t a, uint32_t b) {
    for (uint32_t v : topo.face(f))
      if (canon[v] != a && canon[v] != b) return v;
    return topo.face(f)[0];
  };
  // Overlap needs the normals within ~2.6 degrees: a seam between two
  // triangulations of a slightly non-planar quad is not exactly flat.
  constexpr double kCosFold = 0.999;
  std::vector<uint8_t> hit(topo.num_faces(), 0);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    const glm::dvec3 p = m.points[edges[i].a], q = m.points[edges[i].b];
    for (size_t x = i; x < j; ++x)
      for (size_t y = x + 1; y < j; ++y) {
        const uint32_t f = edges[x].face, g = edges[y].face;
        const glm::dvec3 nf = glm::cross(q - p, m.points[third(f, edges[i].a, edges[i].b)] - p);
        const glm::dvec3 ng = glm::cross(q - p, m.points[third(g, edges[i].a, edges[i].b)] - p);
        const double lf = glm::length(nf), lg = glm::length(ng);
        if (lf == 0.0 || lg == 0.0 || !std::isfinite(lf * lg)) continue;
        if (glm::dot(nf, ng) >= kCosFold * lf * lg) hit[f] = hit[g] = 1;
      }
    i = j;
  }
  return static_cast<size_t>(std::count(hit.begin(), hit.end(), 1));
}

}  // namespace

bool ValidationReport::clean() const {
  return zero_volume_tets == 0 && nonfinite_tets == 0 && duplicate_points == 0 && unused_points == 0 &&
         nonfinite_points == 0 && nonfinite_scalars == 0 && nonmanifold_faces == 0 &&
         coincident_boundary_faces == 0;
}

size_t count_nonfinite_tets(const TetMesh& m) {
  // On the caller's TBB arena. Points first: with every point finite (the
  // usual case) no tet can be otherwise, and the pass over the tets, five
  // times the bytes and scattered, is skipped.
  auto bad = [&](size_t v) { return !finite3(m.points[v]) || (m.has_scalars() && !std::isfinite(m.scalars[v])); };
  const size_t bad_points = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, m.points.size(), 1 << 16), size_t(0),
      [&](const tbb::blocked_range<size_t>& r, size_t n) {
        for (size_t v = r.begin(); v < r.end(); ++v) n += bad(v);
        return n;
      },
      std::plus<size_t>());
  // Cell data: a tet whose own value is not finite.
  auto bad_cell = [&](size_t t) { return m.has_cell_scalars() && !std::isfinite(m.cell_scalars[t]); };
  if (bad_points == 0 && !m.has_cell_scalars()) return 0;
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, m.tets.size(), 1 << 14), size_t(0),
      [&](const tbb::blocked_range<size_t>& r, size_t n) {
        for (size_t t = r.begin(); t < r.end(); ++t)
          n += bad_cell(t) || (bad_points && std::any_of(m.tets[t].begin(), m.tets[t].end(), bad));
        return n;
      },
      std::plus<size_t>());
}

ValidationReport validate(const TetMesh& m, const Topology& topo, double eps) {
  ValidationReport r;
  r.zero_volume_eps = eps;
  for (const auto& p : m.points)
    if (!finite3(p)) ++r.nonfinite_points;
  for (double s : m.scalar_values())
    if (!std::isfinite(s)) ++r.nonfinite_scalars;

  std::vector<uint8_t> used(m.points.size(), 0);
  for (const Tet& t : m.tets) {
    for (uint32_t v : t) used[v] = 1;
    if (!finite3(m.points[t[0]]) || !finite3(m.points[t[1]]) || !finite3(m.points[t[2]]) ||
        !finite3(m.points[t[3]])) {
      ++r.nonfinite_tets;
      continue;
    }
    const bool repeated = t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] ||
                          t[1] == t[3] || t[2] == t[3];
    // Degeneracy is judged against the tet's own size, so it means the same
    // at coordinates of 1e-6 and 1e6.
    double l2 = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const glm::dvec3 d = m.points[t[a]] - m.points[t[b]];
        l2 = std::max(l2, glm::dot(d, d));
      }
    const double v6 = signed_volume6(m, t);
    if (repeated) ++r.repeated_index_tets;
    if (repeated || std::abs(v6) <= eps * l2 * std::sqrt(l2)) {
      ++r.zero_volume_tets;
    } else if (v6 > 0) {
      ++r.positive_tets;
    } else {
      ++r.negative_tets;
    }
    r.volume += std::abs(v6) / 6.0;
  }
  r.unused_points = static_cast<size_t>(std::count(used.begin(), used.end(), 0));
  r.nonmanifold_faces = topo.nonmanifold_faces.size();

  const std::vector<uint32_t> canon = canonical_points(m, &r.duplicate_points);
  r.coincident_boundary_faces = count_coincident_boundary(m, topo, canon);
  return r;
}

}  // namespace zs
