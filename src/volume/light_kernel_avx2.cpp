// light_kernel.h on four doubles per lane (AVX2). This file alone is
// compiled with -mavx2 and includes nothing but the kernel, so no inline
// function compiled for AVX2 can leak into code that runs without it.
#include <immintrin.h>

#include "volume/light_kernel.h"

namespace zs::light {

namespace {

struct Lane4 {
  using Mask = __m256d;
  __m256d v;
  Lane4() = default;
  explicit Lane4(double x) : v(_mm256_set1_pd(x)) {}
  explicit Lane4(__m256d x) : v(x) {}
  friend Lane4 operator+(Lane4 a, Lane4 b) { return Lane4(_mm256_add_pd(a.v, b.v)); }
  friend Lane4 operator-(Lane4 a, Lane4 b) { return Lane4(_mm256_sub_pd(a.v, b.v)); }
  friend Lane4 operator*(Lane4 a, Lane4 b) { return Lane4(_mm256_mul_pd(a.v, b.v)); }
  friend Lane4 operator/(Lane4 a, Lane4 b) { return Lane4(_mm256_div_pd(a.v, b.v)); }
  friend __m256d operator<(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ); }
  friend __m256d operator>(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ); }
  friend __m256d operator<=(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_LE_OQ); }
  // maxpd returns its second operand unless the first is greater: as Lane1.
  friend Lane4 max(Lane4 a, Lane4 b) { return Lane4(_mm256_max_pd(a.v, b.v)); }
  friend Lane4 abs(Lane4 a) {
    return Lane4(_mm256_castsi256_pd(
        _mm256_and_si256(_mm256_castpd_si256(a.v), _mm256_set1_epi64x(0x7fffffffffffffffLL))));
  }
  friend Lane4 select(__m256d m, Lane4 a, Lane4 b) { return Lane4(_mm256_blendv_pd(b.v, a.v, m)); }
  friend Lane4 round_int(Lane4 x) {
    const __m256d c = _mm256_set1_pd(6755399441055744.0);
    return Lane4(_mm256_sub_pd(_mm256_add_pd(x.v, c), c));
  }
  friend Lane4 pow2_int(Lane4 n) {
    // n + 1023 + 2^52 holds n + 1023 in its low mantissa bits.
    const __m256d t = _mm256_add_pd(n.v, _mm256_set1_pd(4503599627370496.0 + 1023.0));
    const __m256i k = _mm256_and_si256(_mm256_castpd_si256(t), _mm256_set1_epi64x(0x000fffffffffffffLL));
    return Lane4(_mm256_castsi256_pd(_mm256_slli_epi64(k, 52)));
  }
  friend void split_exponent(Lane4 w, Lane4* e, Lane4* m) {
    const __m256i u = _mm256_castpd_si256(w.v);
    // The biased exponent as the low bits of 2^52 + e_raw.
    const __m256i eb = _mm256_or_si256(_mm256_srli_epi64(u, 52), _mm256_set1_epi64x(0x4330000000000000LL));
    e->v = _mm256_sub_pd(_mm256_castsi256_pd(eb), _mm256_set1_pd(4503599627370496.0 + 1023.0));
    const __m256i mb = _mm256_or_si256(_mm256_and_si256(u, _mm256_set1_epi64x(0x000fffffffffffffLL)),
                                       _mm256_set1_epi64x(0x3ff0000000000000LL));
    m->v = _mm256_castsi256_pd(mb);
  }
};

}  // namespace

void piece_lights_avx2(const PieceArrays& p, size_t n, double inv_unit) {
  for (size_t i = 0; i < n; i += 4) {
    PieceIn<Lane4> in;
    for (int k = 0; k < 3; ++k) {
      in.c0[k] = Lane4(_mm256_loadu_pd(p.c0[k] + i));
      in.c1[k] = Lane4(_mm256_loadu_pd(p.c1[k] + i));
    }
    in.a0 = Lane4(_mm256_loadu_pd(p.a0 + i));
    in.a1 = Lane4(_mm256_loadu_pd(p.a1 + i));
    in.len = Lane4(_mm256_loadu_pd(p.len + i));
    PieceOut<Lane4> out;
    piece_light(in, inv_unit, &out);
    for (int k = 0; k < 3; ++k) _mm256_storeu_pd(p.rgb[k] + i, out.rgb[k].v);
    _mm256_storeu_pd(p.T + i, out.T.v);
    const int mask = _mm256_movemask_pd(out.ok);
    for (int l = 0; l < 4; ++l) p.ok[i + size_t(l)] = uint8_t((mask >> l) & 1);
  }
}

}  // namespace zs::light
