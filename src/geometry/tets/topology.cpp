#include "geometry/tets/topology.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

namespace {

// One (tet, local face) record keyed by its sorted vertex triple.
struct FaceRec {
  uint32_t b, c;  // the two larger vertices (the smallest is the bucket)
  uint32_t tet;
  uint32_t local;  // face opposite local vertex `local`
};

}  // namespace

Topology build_topology(const TetMesh& m) {
  Topology topo;
  const size_t nv = m.points.size();
  const size_t nt = m.tets.size();

  // Bucket the 4·nt face records by their smallest vertex (counting sort),
  // then sort each small bucket by the other two: linear-ish, and far faster
  // than one global sort for meshes of millions of tets.
  std::vector<uint32_t> start(nv + 1, 0);
  auto sorted3 = [](uint32_t a, uint32_t b, uint32_t c) {
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return std::array<uint32_t, 3>{a, b, c};
  };
  auto face_of = [&](const Tet& t, int k) {
    // Face opposite local vertex k.
    static constexpr int kOther[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    return sorted3(t[kOther[k][0]], t[kOther[k][1]], t[kOther[k][2]]);
  };
  for (const Tet& t : m.tets)
    for (int k = 0; k < 4; ++k) ++start[face_of(t, k)[0] + 1];
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];

  std::vector<FaceRec> recs(4 * nt);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t ti = 0; ti < nt; ++ti)
      for (uint32_t k = 0; k < 4; ++k) {
        auto f = face_of(m.tets[ti], k);
        recs[fill[f[0]]++] = {f[1], f[2], ti, k};
      }
  }

  topo.tet_faces.assign(nt, {kNoTet, kNoTet, kNoTet, kNoTet});
  topo.faces.reserve(2 * nt + nt / 4);
  topo.face_tets.reserve(2 * nt + nt / 4);
  for (uint32_t a = 0; a < nv; ++a) {
    FaceRec* lo = recs.data() + start[a];
    FaceRec* hi = recs.data() + start[a + 1];
    std::sort(lo, hi, [](const FaceRec& x, const FaceRec& y) {
      return x.b != y.b ? x.b < y.b : (x.c != y.c ? x.c < y.c : x.tet < y.tet);
    });
    for (FaceRec* r = lo; r < hi;) {
      FaceRec* e = r + 1;
      while (e < hi && e->b == r->b && e->c == r->c) ++e;
      const uint32_t fid = static_cast<uint32_t>(topo.faces.size());
      topo.faces.push_back({a, r->b, r->c});
      topo.face_tets.push_back({r->tet, e - r > 1 ? r[1].tet : kNoTet});
      if (e - r > 2) topo.nonmanifold_faces.push_back(fid);
      if (e - r == 1) ++topo.num_boundary_faces;
      for (FaceRec* q = r; q < e; ++q) topo.tet_faces[q->tet][q->local] = fid;
      r = e;
    }
  }

  // Use sets: each face is listed under each of its (distinct) vertices.
  topo.use_offsets.assign(nv + 1, 0);
  for (const auto& f : topo.faces) {
    ++topo.use_offsets[f[0] + 1];
    if (f[1] != f[0]) ++topo.use_offsets[f[1] + 1];
    if (f[2] != f[1]) ++topo.use_offsets[f[2] + 1];
  }
  for (size_t v = 0; v < nv; ++v) topo.use_offsets[v + 1] += topo.use_offsets[v];
  topo.use_faces.resize(topo.use_offsets[nv]);
  std::vector<uint32_t> fill(topo.use_offsets.begin(), topo.use_offsets.end() - 1);
  for (uint32_t fi = 0; fi < topo.faces.size(); ++fi) {
    const auto& f = topo.faces[fi];
    topo.use_faces[fill[f[0]]++] = fi;
    if (f[1] != f[0]) topo.use_faces[fill[f[1]]++] = fi;
    if (f[2] != f[1]) topo.use_faces[fill[f[2]]++] = fi;
  }

  topo.tet_degenerate.resize(nt);
  topo.tet_scalar_range.resize(nt);
  for (size_t t = 0; t < nt; ++t) {
    const Tet& tet = m.tets[t];
    double lo = INFINITY, hi = -INFINITY, l2 = 0;
    bool finite = true;
    for (int a = 0; a < 4; ++a) {
      const glm::dvec3& p = m.points[tet[a]];
      const double s = m.has_scalars() ? m.scalars[tet[a]] : 0.0;
      finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(s);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
      for (int b = a + 1; b < 4; ++b) {
        const glm::dvec3 d = p - m.points[tet[b]];
        l2 = std::max(l2, glm::dot(d, d));
      }
    }
    // Same relative criterion as validation (validate.h).
    topo.tet_degenerate[t] = !finite || !(std::abs(signed_volume6(m, tet)) > 1e-10 * l2 * std::sqrt(l2));
    topo.tet_scalar_range[t] = {lo, hi};
  }
  return topo;
}

}  // namespace zs
