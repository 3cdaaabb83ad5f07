#include "geometry/tets/generate/tet_ops.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

namespace zs {

// Faces of a positively oriented tet, wound outward; face k is opposite vertex k.
static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

void orient_positive(TetMesh& m) {
  for (Tet& t : m.tets)
    if (signed_volume6(m, t) < 0) std::swap(t[2], t[3]);
}

size_t remove_degenerate(TetMesh& m, double rel_eps) {
  auto longest_edge2 = [&](const Tet& t) {
    double l = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        glm::dvec3 e = m.points[t[i]] - m.points[t[j]];
        l = std::max(l, glm::dot(e, e));
      }
    return l;
  };
  const size_t before = m.tets.size();
  std::erase_if(m.tets, [&](const Tet& t) {
    double l2 = longest_edge2(t);
    return !(std::abs(signed_volume6(m, t)) > rel_eps * l2 * std::sqrt(l2));
  });

  // Compact points so no generator leaves unused vertices behind.
  // Used points keep their relative order.
  std::vector<uint32_t> remap(m.points.size(), UINT32_MAX);
  for (const Tet& t : m.tets)
    for (uint32_t v : t) remap[v] = 0;
  uint32_t next = 0;
  for (uint32_t& r : remap)
    if (r == 0) r = next++;
  if (next != m.points.size()) {
    for (Tet& t : m.tets)
      for (uint32_t& v : t) v = remap[v];
    std::vector<glm::dvec3> pts(next);
    std::vector<double> sc(m.has_scalars() ? next : 0);
    for (size_t i = 0; i < remap.size(); ++i) {
      if (remap[i] == UINT32_MAX) continue;
      pts[remap[i]] = m.points[i];
      if (!sc.empty()) sc[remap[i]] = m.scalars[i];
    }
    m.points = std::move(pts);
    m.scalars = std::move(sc);
  }
  return before - m.tets.size();
}

std::vector<std::array<uint32_t, 3>> boundary_faces(const TetMesh& m) {
  // Sort (sorted key, tet, face) records instead of hashing: millions of
  // faces sort faster than they hash.
  struct Rec {
    std::array<uint32_t, 3> key;
    uint32_t tet;
    uint8_t face;
  };
  std::vector<Rec> recs;
  recs.reserve(m.tets.size() * 4);
  for (uint32_t t = 0; t < m.tets.size(); ++t)
    for (uint8_t f = 0; f < 4; ++f) {
      std::array<uint32_t, 3> k;
      for (int i = 0; i < 3; ++i) k[i] = m.tets[t][kFace[f][i]];
      std::sort(k.begin(), k.end());
      recs.push_back({k, t, f});
    }
  std::sort(recs.begin(), recs.end(), [](const Rec& a, const Rec& b) { return a.key < b.key; });

  std::vector<std::array<uint32_t, 3>> out;
  for (size_t i = 0; i < recs.size();) {
    size_t j = i + 1;
    while (j < recs.size() && recs[j].key == recs[i].key) ++j;
    if (j - i == 1) {
      const Tet& t = m.tets[recs[i].tet];
      const int* f = kFace[recs[i].face];
      std::array<uint32_t, 3> tri = {t[f[0]], t[f[1]], t[f[2]]};
      if (signed_volume6(m, t) < 0) std::swap(tri[1], tri[2]);
      out.push_back(tri);
    }
    i = j;
  }
  return out;
}

double total_volume(const TetMesh& m) {
  double v = 0;
  for (const Tet& t : m.tets) v += std::abs(signed_volume6(m, t));
  return v / 6.0;
}

void finalize_generated(TetMesh& m) {
  orient_positive(m);
  size_t removed = remove_degenerate(m);
  if (removed) m.notes.push_back("generator: dropped " + std::to_string(removed) + " degenerate tets");
  if (m.tets.empty()) throw std::runtime_error("mesh generation produced no tetrahedra");
}

}  // namespace zs
