// Compositing translucent sphere fragments (spheres digest §2.3): the order
// of fragments along a ray, front-to-back "under" compositing of
// premultiplied colours (Eq. 4.1, §2.3.4), the incomplete-image stop
// (Eq. 4.2, §2.3.7), back-to-front compositing for dual peeling, and
// Meshkin's weighted sum.
//
// Every mode composites with these functions, in this order of operations,
// so `peel` run to completion gives `sorted`'s image bit for bit.
#pragma once

#include <algorithm>
#include <cstdint>

namespace zs {

// A fragment's place along its ray: view depth, then sphere index, then the
// entry before the exit (code = 2·id + exit). A total order, the reference's
// (SphereCrossing), so coincident surfaces composite the same way
// whatever the tiles, threads or mode.
struct FragKey {
  double z;
  uint64_t code;
};
inline bool operator<(const FragKey& a, const FragKey& b) { return a.z < b.z || (a.z == b.z && a.code < b.code); }
inline bool operator==(const FragKey& a, const FragKey& b) { return a.z == b.z && a.code == b.code; }
inline uint64_t frag_code(uint32_t id, bool exit) { return (uint64_t(id) << 1) | uint64_t(exit); }
inline uint32_t frag_id(uint64_t code) { return uint32_t(code >> 1); }
inline bool frag_exit(uint64_t code) { return code & 1; }
constexpr FragKey kKeyMin{-__builtin_inf(), 0}, kKeyMax{__builtin_inf(), ~uint64_t(0)};

// Eq. 4.1, I = C·(1 − D_A) + D, C premultiplied: the fragment goes under
// what is in front of it.
inline void composite_under(double acc[4], const double c[4]) {
  const double k = 1.0 - acc[3];
  for (int i = 0; i < 4; ++i) acc[i] = c[i] * k + acc[i];
}

// Back-to-front (dual peeling's back layers): the fragment goes over what
// is behind it, B = C + (1 − C_A)·B.
inline void composite_over(double acc[4], const double c[4]) {
  const double k = 1.0 - c[3];
  for (int i = 0; i < 4; ++i) acc[i] = c[i] + k * acc[i];
}

// Eq. 4.2: the pixel can change by at most 1 − A from here on; with a
// tolerance of t 8-bit levels it stops once 1 − A <= t/510 (t/2 levels).
// t = 0 never stops.
inline double stop_threshold(double tolerance) { return tolerance > 0 ? tolerance / 510.0 : -1.0; }
inline bool saturated(const double acc[4], double threshold) { return 1.0 - acc[3] <= threshold; }

// Alpha exactly 1 in double: composite_under then adds c·0 to every
// channel, so nothing behind can change a bit and the pixel may end at
// any tolerance, 0 included. This is no approximation; it is what lets an
// exact composite stop after ~100 fragments of alpha 0.3 instead of
// walking thousands.
inline bool opaque_now(const double acc[4]) { return acc[3] == 1.0; }

// Meshkin's weighted sum (Bavoil & Myers 2008's statement of it): the
// order-independent terms of the expanded blend, X = Σ C_i·α_i (premultiplied
// colours summed, alpha included) and the background weighted by
// 1 − Σ α_i, each channel clamped to [0, 1]. Exact for one fragment; where
// Σ α > 1 the background weight goes negative and overlaps saturate (the
// seed's Figure 14, spheres digest §2.3.6). The digest's printed formula
// (W + X − W·X_A + W·Z_A + W·Y_A·Z_A) gives 2W + C·α for one fragment, so it
// is not the one used.
inline void weighted_sum(const double x[4], const double w[4], double out[4]) {
  const double k = 1.0 - x[3];
  for (int i = 0; i < 4; ++i) out[i] = std::clamp(x[i] + w[i] * k, 0.0, 1.0);
}

}  // namespace zs
