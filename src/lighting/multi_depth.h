// The n-SM pass (shadow-maps digest §2.6.5–2.6.6, "pass 2"): one
// image-space pass over a shadow map that gives every texel n depths, its
// own z_c first.
//   n = 1: z_c (the classic map);
//   n = 2: z_c and the maximum (or minimum, `select`) of its 3×3 neighbourhood;
//   n = 3: z_c, the maximum and the minimum of the 3×3 neighbourhood;
//   n = 4..9: z_c and n − 1 fixed neighbours spread evenly around it: ring
//             position round(8i/(n − 1)) of the 8 neighbours counter-clockwise
//             from +x (n = 4: at 0°, 135°, 225°, close to the 120° spacing
//             the digest infers, §2.6.5; n = 5: the four axis neighbours;
//             n = 9: all eight).
// Borders clamp to the edge. Cost: size² × q reads (q = 9, or n − 1 + 1).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "lighting/shadow_settings.h"

namespace zs {

constexpr uint32_t kMaxDepths = 9;

// `z`: size·size depths, row-major. `out`: size·size·n, texel-major.
void build_multi_depth(const float* z, uint32_t size, uint32_t n, DepthSelect select, float* out);

// The fixed pattern of n >= 4: n − 1 texel offsets.
std::vector<std::pair<int, int>> depth_pattern(uint32_t n);

}  // namespace zs
