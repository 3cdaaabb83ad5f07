#include "render/volume/sweep_order.h"

#include <algorithm>
#include <cmath>

namespace zs {

bool pixel_range(const ScreenVertex v[3], uint32_t w, uint32_t h, int* i0, int* i1, int* j0, int* j1) {
  const double min_x = std::min({v[0].x, v[1].x, v[2].x}), max_x = std::max({v[0].x, v[1].x, v[2].x});
  const double min_y = std::min({v[0].y, v[1].y, v[2].y}), max_y = std::max({v[0].y, v[1].y, v[2].y});
  // Clamp in double first so huge coordinates never overflow the int
  // conversion; a NaN box compares false and is dropped.
  if (!(max_x >= 0 && min_x <= double(w) - 1 && max_y >= 0 && min_y <= double(h) - 1)) return false;
  *i0 = int(std::ceil(std::max(min_x, 0.0)));
  *i1 = int(std::floor(std::min(max_x, double(w) - 1)));
  *j0 = int(std::ceil(std::max(min_y, 0.0)));
  *j1 = int(std::floor(std::min(max_y, double(h) - 1)));
  return *i0 <= *i1 && *j0 <= *j1;
}

namespace {

enum class Cover { Yes, Degenerate, Offscreen };

// Whether a triangle can produce fragments, and the tiles it touches.
Cover tile_box(const ScreenVertex v[3], const ScreenTiling& t, TileBox* box) {
  const double det = screen_det(v);
  if (det == 0 || !std::isfinite(det)) return Cover::Degenerate;
  int i0, i1, j0, j1;
  if (!pixel_range(v, t.width, t.height, &i0, &i1, &j0, &j1)) return Cover::Offscreen;
  *box = {uint32_t(i0) / t.tile, uint32_t(i1) / t.tile, uint32_t(j0) / t.tile, uint32_t(j1) / t.tile};
  return Cover::Yes;
}

constexpr uint32_t kDropped = UINT32_MAX;

}  // namespace

SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       const std::vector<uint8_t>& done, std::vector<VertexHeap::Entry> events,
                       const std::vector<NearTriangle>& near, double z_origin, const ScreenTiling& tiling) {
  SweepItems it;
  auto count = [&](Cover c) { ++(c == Cover::Degenerate ? it.degenerate : it.offscreen); };
  for (size_t k = 0; k < near.size(); ++k) {
    TileBox box;
    const Cover c = tile_box(near[k].v, tiling, &box);
    if (c != Cover::Yes) {
      count(c);
      continue;
    }
    float zmax = -INFINITY;
    for (const ScreenVertex& v : near[k].v) zmax = std::max(zmax, float(v.z - z_origin));
    it.id.push_back(kNearItem | uint32_t(k));
    it.tri.push_back({0, 0, 0});
    it.z_sweep.push_back(-INFINITY);
    it.z_max.push_back(zmax);
    it.box.push_back(box);
  }
  // The sweep: each event vertex's rank in heap order, and the plane's depth there.
  const size_t n_events = events.size();
  std::vector<uint32_t> rank(sv.size(), kDropped);
  std::vector<float> z_at(n_events);
  VertexHeap heap;
  heap.assign(std::move(events));
  for (uint32_t r = 0; r < n_events; ++r) {
    const VertexHeap::Entry ev = heap.pop();
    rank[ev.v] = r;
    z_at[r] = float(ev.z - z_origin);
  }
  // A face is projected when the first of its vertices is swept: at the
  // smallest rank among them. Faces of one vertex follow in id order (its use
  // set's order). Counting sort by that rank, dropping faces that cannot
  // produce a fragment.
  const uint32_t nf = uint32_t(topo.num_faces());
  std::vector<uint32_t> key(nf, kDropped);
  std::vector<uint32_t> start(n_events + 1, 0);
  std::vector<TileBox> kept_box;  // the kept faces' boxes, in face order
  kept_box.reserve(nf / 2);
  for (uint32_t f = 0; f < nf; ++f) {
    if (done[f] || cls[f] == FaceClass::Culled) continue;
    const auto& fv = topo.faces[f];
    const uint32_t r = std::min({rank[fv[0]], rank[fv[1]], rank[fv[2]]});
    if (r == kDropped) continue;  // no vertex in front of the near plane: clipped
    const ScreenVertex v[3] = {sv[fv[0]], sv[fv[1]], sv[fv[2]]};
    TileBox box;
    const Cover c = tile_box(v, tiling, &box);
    if (c != Cover::Yes) {
      count(c);
      continue;
    }
    key[f] = r;
    ++start[r + 1];
    kept_box.push_back(box);
  }
  for (size_t r = 0; r < n_events; ++r) start[r + 1] += start[r];
  const size_t base = it.size(), total = base + start[n_events];
  it.id.resize(total);
  it.tri.resize(total);
  it.z_sweep.resize(total);
  it.z_max.resize(total);
  it.box.resize(total);
  size_t kept = 0;
  for (uint32_t f = 0; f < nf; ++f) {
    const uint32_t r = key[f];
    if (r == kDropped) continue;
    const size_t k = base + start[r]++;
    const auto& fv = topo.faces[f];
    it.box[k] = kept_box[kept++];
    it.id[k] = f;
    it.tri[k] = fv;
    it.z_sweep[k] = z_at[r];
    it.z_max[k] = float(std::max({sv[fv[0]].z, sv[fv[1]].z, sv[fv[2]].z}) - z_origin);
  }
  return it;
}

}  // namespace zs
