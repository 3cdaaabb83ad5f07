#include "volume/sweep_order.h"

#include <algorithm>
#include <cmath>

namespace zs {

SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       std::vector<uint8_t> done, std::vector<VertexHeap::Entry> events,
                       const std::vector<NearTriangle>& near, double z_origin) {
  SweepItems it;
  const size_t n_events = events.size();
  it.id.reserve(near.size() + topo.num_faces());
  it.z_sweep.reserve(it.id.capacity());
  it.z_max.reserve(it.id.capacity());
  for (size_t k = 0; k < near.size(); ++k) {
    float zmax = -INFINITY;
    for (const ScreenVertex& v : near[k].v) zmax = std::max(zmax, float(v.z - z_origin));
    it.id.push_back(kNearItem | uint32_t(k));
    it.z_sweep.push_back(-INFINITY);
    it.z_max.push_back(zmax);
  }
  VertexHeap heap;
  heap.assign(std::move(events));
  for (size_t k = 0; k < n_events; ++k) {
    const VertexHeap::Entry ev = heap.pop();
    const float z_sweep = float(ev.z - z_origin);
    for (uint32_t f : topo.use_set(ev.v)) {
      if (done[f] || cls[f] == FaceClass::Culled) continue;
      done[f] = 1;
      const auto& fv = topo.faces[f];
      const double zmax = std::max({sv[fv[0]].z, sv[fv[1]].z, sv[fv[2]].z});
      it.id.push_back(f);
      it.z_sweep.push_back(z_sweep);
      it.z_max.push_back(float(zmax - z_origin));
    }
  }
  return it;
}

}  // namespace zs
