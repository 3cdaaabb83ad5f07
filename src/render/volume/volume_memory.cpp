#include "render/volume/volume_memory.h"

#include <algorithm>
#include <cstdio>

#include "base/util/bytes_str.h"
#include "geometry/tets/topology.h"
#include "render/volume/render_plan.h"

namespace zs {

uint64_t VolumeMemory::peak() const { return mesh + std::max(topology_build, topology + per_view); }

VolumeMemory estimate_volume_memory(uint64_t points, uint64_t tets, bool scalars, uint64_t faces,
                                    bool cell_scalars) {
  VolumeMemory m;
  m.tets = tets;
  m.mesh = points * (24 + (scalars ? 8 : 0)) + tets * (16 + (cell_scalars ? 8 : 0));
  m.topology = faces ? faces * sizeof(FaceTets) + tets : topology_bytes(tets);
  m.topology_build = topology_build_peak_bytes(points, tets);
  if (!faces) faces = tets * 21 / 10;
  m.per_view = zsweep_shared_bytes(points, faces) + faces * 4;  // bins: one entry per item
  return m;
}

std::string volume_memory_summary(const VolumeMemory& m) {
  char b[256];
  std::snprintf(b, sizeof b, "%s at peak (mesh %s, topology %s, one view %s), %.0f bytes per tet",
                bytes_str(m.peak()).c_str(), bytes_str(m.mesh).c_str(), bytes_str(m.topology).c_str(),
                bytes_str(m.per_view).c_str(), m.bytes_per_tet());
  return b;
}

}  // namespace zs
