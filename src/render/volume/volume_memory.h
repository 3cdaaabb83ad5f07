// What a volume render of a mesh holds, from its counts alone: the mesh, the
// topology every frame shares (and the most its build holds at once), and
// one view's set-up (vertices in view space, face classes, sweep items, one
// bin entry per item). The fragment pools come on top, sized from what the
// memory budget leaves (render_plan.h). `zsweep mesh info` prints it; a
// render refuses a mesh that cannot fit its budget before building anything.
#pragma once

#include <cstdint>
#include <string>

namespace zs {

struct VolumeMemory {
  uint64_t tets = 0;
  uint64_t mesh = 0;            // points and tets, with their scalars
  uint64_t topology = 0;        // kept for every frame
  uint64_t topology_build = 0;  // held while it is built, on top of the mesh
  uint64_t per_view = 0;        // one frame's set-up, on top of mesh and topology
  uint64_t peak() const;        // the most held at once, without fragment pools
  double bytes_per_tet() const { return tets ? double(peak()) / double(tets) : 0.0; }
};

// faces = 0: estimated (2.1 per tet, a 5-tet grid split's ratio).
// scalars: point scalars; cell_scalars: one per tet.
VolumeMemory estimate_volume_memory(uint64_t points, uint64_t tets, bool scalars, uint64_t faces = 0,
                                    bool cell_scalars = false);

// "2381.2 MiB at peak (mesh 915.5 MiB, topology 715.3 MiB, one view 750.4 MiB), 61 bytes per tet".
std::string volume_memory_summary(const VolumeMemory& m);

}  // namespace zs
