#include "render/surfaces/rgba_store.h"

#include <cstring>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace zs {

void store_rgba(int n, const float* r, const float* g, const float* b, const uint32_t* id, uint32_t none,
                const float* bg, float* __restrict out) {
  int i = 0;
#if defined(__AVX512F__)
  // 16 pixels at a time: the colour planes and alpha transposed into RGBA
  // quads by unpacks and 128-bit lane shuffles, the background blended in
  // by a mask of four lanes per pixel, four 64-byte stores. (The compiler's
  // own interleave, all permutes, was slower than the scalar loop below.)
  static constexpr uint16_t kQuad[16] = {0x0000, 0x000f, 0x00f0, 0x00ff, 0x0f00, 0x0f0f, 0x0ff0, 0x0fff,
                                         0xf000, 0xf00f, 0xf0f0, 0xf0ff, 0xff00, 0xff0f, 0xfff0, 0xffff};
  const __m512 back = _mm512_broadcast_f32x4(_mm_loadu_ps(bg)), one = _mm512_set1_ps(1.f);
  const __m512i empty = _mm512_set1_epi32(int(none));
  for (; i + 16 <= n; i += 16) {
    const __m512 vr = _mm512_loadu_ps(r + i), vg = _mm512_loadu_ps(g + i), vb = _mm512_loadu_ps(b + i);
    const __m512d rg0 = _mm512_castps_pd(_mm512_unpacklo_ps(vr, vg)), rg1 = _mm512_castps_pd(_mm512_unpackhi_ps(vr, vg));
    const __m512d ba0 = _mm512_castps_pd(_mm512_unpacklo_ps(vb, one)), ba1 = _mm512_castps_pd(_mm512_unpackhi_ps(vb, one));
    // p_k: pixels k, k + 4, k + 8 and k + 12, one per 128-bit lane.
    const __m512 p0 = _mm512_castpd_ps(_mm512_unpacklo_pd(rg0, ba0)), p1 = _mm512_castpd_ps(_mm512_unpackhi_pd(rg0, ba0));
    const __m512 p2 = _mm512_castpd_ps(_mm512_unpacklo_pd(rg1, ba1)), p3 = _mm512_castpd_ps(_mm512_unpackhi_pd(rg1, ba1));
    const __m512 t0 = _mm512_shuffle_f32x4(p0, p1, 0x44), t1 = _mm512_shuffle_f32x4(p2, p3, 0x44);
    const __m512 t2 = _mm512_shuffle_f32x4(p0, p1, 0xEE), t3 = _mm512_shuffle_f32x4(p2, p3, 0xEE);
    const __m512 q[4] = {_mm512_shuffle_f32x4(t0, t1, 0x88), _mm512_shuffle_f32x4(t0, t1, 0xDD),
                         _mm512_shuffle_f32x4(t2, t3, 0x88), _mm512_shuffle_f32x4(t2, t3, 0xDD)};
    const unsigned m = _mm512_cmpeq_epi32_mask(_mm512_loadu_si512(id + i), empty);
    for (int k = 0; k < 4; ++k)
      _mm512_storeu_ps(out + 4 * size_t(i + 4 * k), _mm512_mask_mov_ps(q[k], __mmask16(kQuad[(m >> (4 * k)) & 15]), back));
  }
#endif
  // One 16-byte store a pixel.
  typedef float F4 __attribute__((vector_size(16)));
  const F4 bk = {bg[0], bg[1], bg[2], bg[3]};
  for (; i < n; ++i) {
    const F4 px = {r[i], g[i], b[i], 1.f};
    const F4 v = id[i] == none ? bk : px;
    std::memcpy(out + 4 * size_t(i), &v, sizeof v);
  }
}

}  // namespace zs
