// The sweep's event list (B-Convert digest §1.1, stage 1): the vertices that
// start a face, in the order the sweep plane meets them — by view depth, ties
// by vertex id, -0 with +0. The digest keeps them in a heap because its sweep
// may insert events as it goes; ours never does (the near-plane clip adds
// faces, not events: near_clip.h), so the heap's pop order is one sort of the
// whole list, which runs on every thread (a heap pops on one). The order, and
// so every image, is the heap's.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace zs {

struct SweepEvent {
  double z;
  uint32_t v;
};

// The events as one 128-bit key ordered as (z, v): the depth's bits mapped so
// that unsigned order is numeric order (-0 as +0), then the vertex id.
using SweepKey = unsigned __int128;
inline SweepKey sweep_key(double z, uint32_t v) {
  if (z == 0) z = 0;  // -0 sorts with +0
  uint64_t u;
  std::memcpy(&u, &z, 8);
  u = (u >> 63) ? ~u : (u | (uint64_t(1) << 63));
  return (SweepKey(u) << 32) | v;
}
inline SweepEvent sweep_event(SweepKey k) {
  uint64_t u = uint64_t(k >> 32);
  u = (u >> 63) ? (u & ~(uint64_t(1) << 63)) : ~u;
  double z;
  std::memcpy(&z, &u, 8);
  return {z, uint32_t(k)};
}

// The events' keys in sweep order (on the calling thread's TBB arena).
std::vector<SweepKey> sorted_events(const std::vector<SweepEvent>& events);

}  // namespace zs
