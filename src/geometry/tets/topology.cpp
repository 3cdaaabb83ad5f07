#include "geometry/tets/topology.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace zs {

namespace {

// One face record of a bucket being sorted: the face's two larger vertices
// (the bucket is its smallest) and tet << 2 | local face.
struct Keyed {
  uint32_t b, c, rec;
  bool operator<(const Keyed& o) const { return b != o.b ? b < o.b : (c != o.c ? c < o.c : rec < o.rec); }
};

// Counts per vertex, then a prefix sum: start[v] .. start[v + 1].
void prefix_sum(std::vector<uint32_t>& v) {
  uint32_t run = 0;
  for (uint32_t& x : v) {
    const uint32_t c = x;
    x = run;
    run += c;
  }
}

constexpr size_t kGrain = 1 << 14;

}  // namespace

Topology build_topology(const TetMesh& m) {
  Topology topo;
  const size_t nv = m.points.size();
  const size_t nt = m.tets.size();
  if (nt >= kMaxTopologyTets)
    throw std::runtime_error("the mesh has " + std::to_string(nt) + " tets; at most " +
                             std::to_string(kMaxTopologyTets - 1) + " fit the face records");
  topo.tets = std::span<const Tet>(m.tets);
  const Tet* tets = m.tets.data();

  // Face records bucketed by their smallest vertex (a counting sort: counts,
  // prefix, fill), each record 4 bytes (tet << 2 | k): the vertices are read
  // back from the tet. Buckets are filled in any order and then sorted by the
  // full key (b, c, tet, k), so the result does not depend on the threads.
  // Three of a tet's faces hold its smallest vertex and the fourth its
  // second smallest: two counter updates per tet, not four.
  struct Mins {
    uint32_t k0, m0, m1;  // the smallest vertex's slot, it, and the smallest of the rest
  };
  auto mins = [](const Tet& t) {
    uint32_t k0 = 0;
    for (uint32_t k = 1; k < 4; ++k)
      if (t[k] < t[k0]) k0 = k;
    uint32_t m1 = UINT32_MAX;
    for (uint32_t k = 0; k < 4; ++k)
      if (k != k0) m1 = std::min(m1, t[k]);
    return Mins{k0, t[k0], m1};
  };
  std::vector<uint32_t> start(nv + 1, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t < r.end(); ++t) {
      const Mins x = mins(tets[t]);
      std::atomic_ref<uint32_t>(start[x.m0]).fetch_add(3, std::memory_order_relaxed);
      std::atomic_ref<uint32_t>(start[x.m1]).fetch_add(1, std::memory_order_relaxed);
    }
  });
  prefix_sum(start);  // start[nv] = 4 nt
  UninitVector<uint32_t> recs(4 * nt);  // every record is written by the fill
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, kGrain), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t t = r.begin(); t < r.end(); ++t) {
        const Mins x = mins(tets[t]);
        uint32_t* at = recs.data() + std::atomic_ref<uint32_t>(fill[x.m0]).fetch_add(3, std::memory_order_relaxed);
        for (uint32_t k = 0; k < 4; ++k)
          if (k != x.k0) *at++ = uint32_t(t) << 2 | k;
        recs[std::atomic_ref<uint32_t>(fill[x.m1]).fetch_add(1, std::memory_order_relaxed)] = uint32_t(t) << 2 | x.k0;
      }
    });
  }

  // Sort each bucket and count its unique faces (into `uniq`, then their
  // first ids by a prefix sum: faces are numbered in (a, b, c) order). Each
  // face's first record is marked, so the pass below reads no tet.
  std::vector<uint32_t> uniq(nv + 1, 0);
  UninitVector<uint8_t> first(4 * nt);
  tbb::enumerable_thread_specific<std::vector<Keyed>> scratch;
  auto sort_bucket = [&](uint32_t a, std::vector<Keyed>& ks) {
    ks.clear();
    for (uint32_t i = start[a]; i < start[a + 1]; ++i) {
      const auto f = Topology::tet_face(tets[recs[i] >> 2], recs[i] & 3);
      ks.push_back({f[1], f[2], recs[i]});
    }
    std::sort(ks.begin(), ks.end());
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, kGrain / 4), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<Keyed>& ks = scratch.local();
    for (size_t a = r.begin(); a < r.end(); ++a) {
      sort_bucket(uint32_t(a), ks);
      uint32_t n = 0;
      for (size_t i = 0; i < ks.size(); ++i) {
        const bool starts = i == 0 || ks[i].b != ks[i - 1].b || ks[i].c != ks[i - 1].c;
        recs[start[a] + i] = ks[i].rec;
        first[start[a] + i] = starts;
        n += starts;
      }
      uniq[a] = n;
    }
  });
  prefix_sum(uniq);
  const size_t nf = uniq[nv];

  // Each face's tets: the sorted records of one face are adjacent.
  topo.face_tets.resize(nf);
  tbb::combinable<size_t> boundary;
  tbb::enumerable_thread_specific<std::vector<uint32_t>> nonmanifold;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, kGrain / 4), [&](const tbb::blocked_range<size_t>& r) {
    size_t nb = 0;
    std::vector<uint32_t>& nm = nonmanifold.local();
    for (size_t a = r.begin(); a < r.end(); ++a) {
      uint32_t fid = uniq[a];
      for (uint32_t q = start[a], hi = start[a + 1]; q < hi; ++fid) {
        uint32_t e = q + 1;
        while (e < hi && !first[e]) ++e;
        topo.face_tets[fid] = {recs[q], e - q > 1 ? recs[q + 1] >> 2 : kNoTet};
        if (e - q > 2) nm.push_back(fid);
        nb += e - q == 1;
        q = e;
      }
    }
    boundary.local() += nb;
  });
  topo.num_boundary_faces = boundary.combine(std::plus<size_t>());
  for (const auto& v : nonmanifold) topo.nonmanifold_faces.insert(topo.nonmanifold_faces.end(), v.begin(), v.end());
  std::sort(topo.nonmanifold_faces.begin(), topo.nonmanifold_faces.end());
  UninitVector<uint32_t>().swap(recs);
  UninitVector<uint8_t>().swap(first);

  topo.tet_degenerate.resize(nt);
  tbb::combinable<size_t> nonfinite;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    size_t n = 0;
    for (size_t t = r.begin(); t < r.end(); ++t) {
      const Tet& tet = tets[t];
      double l2 = 0;
      bool finite = !m.has_cell_scalars() || std::isfinite(m.cell_scalars[t]);
      for (int a = 0; a < 4; ++a) {
        const glm::dvec3& p = m.points[tet[a]];
        const double s = m.has_scalars() ? m.scalars[tet[a]] : 0.0;
        finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(s);
        for (int b = a + 1; b < 4; ++b) {
          const glm::dvec3 d = p - m.points[tet[b]];
          l2 = std::max(l2, glm::dot(d, d));
        }
      }
      // Same relative criterion as validation (validate.h).
      topo.tet_degenerate[t] = !finite || !(std::abs(signed_volume6(m, tet)) > 1e-10 * l2 * std::sqrt(l2));
      n += !finite;
    }
    nonfinite.local() += n;
  });
  topo.num_nonfinite_tets = nonfinite.combine(std::plus<size_t>());
  return topo;
}

std::vector<std::array<uint32_t, 4>> build_tet_faces(const TetMesh& m, const Topology& topo) {
  // Faces are numbered in (a, b, c) order: the faces of smallest vertex a are
  // a contiguous run, searched by (b, c).
  const size_t nv = m.points.size(), nf = topo.num_faces();
  std::vector<uint32_t> first(nv + 1, 0);
  for (uint32_t f = 0; f < nf; ++f) ++first[topo.face(f)[0] + 1];
  for (size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<std::array<uint32_t, 4>> out(m.tets.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, m.tets.size(), kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t < r.end(); ++t)
      for (uint32_t k = 0; k < 4; ++k) {
        const auto key = Topology::tet_face(m.tets[t], k);
        uint32_t lo = first[key[0]], hi = first[key[0] + 1];
        while (lo < hi) {
          const uint32_t mid = lo + (hi - lo) / 2;
          const auto f = topo.face(mid);
          if (f[1] < key[1] || (f[1] == key[1] && f[2] < key[2])) lo = mid + 1;
          else hi = mid;
        }
        out[t][k] = lo;
      }
  });
  return out;
}

uint64_t topology_bytes(uint64_t tets) {
  const uint64_t faces = tets * 21 / 10;
  return faces * sizeof(FaceTets) + tets;
}

uint64_t topology_build_peak_bytes(uint64_t points, uint64_t tets) {
  // Counts, fill cursors and unique counts per vertex; 4-byte records and
  // their 1-byte first-of-face marks per tet face; the faces, allocated while
  // the records live.
  return 3 * (points + 1) * 4 + 20 * tets + topology_bytes(tets) - tets;
}

}  // namespace zs
