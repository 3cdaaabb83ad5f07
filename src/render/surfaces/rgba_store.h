// A shading batch's colours written as interleaved R, G, B, A floats (the
// tile layout of the RGBA-only, 8-bit outputs): alpha 1 where a triangle
// covers the pixel, the background's premultiplied RGBA where none does.
#pragma once

#include <cstdint>

namespace zs {

// out[4i .. 4i+3] = (r[i], g[i], b[i], 1), or bg[0..3] where id[i] == none.
void store_rgba(int n, const float* r, const float* g, const float* b, const uint32_t* id, uint32_t none,
                const float* bg, float* __restrict out);

}  // namespace zs
