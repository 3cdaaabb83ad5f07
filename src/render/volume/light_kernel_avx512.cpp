// light_kernel.h on eight doubles per lane (AVX-512F). Like the AVX2 file,
// compiled alone with its instruction set and chosen at run time.
#include <immintrin.h>

#include "base/optics/lane_pair.h"
#include "base/optics/light_kernel.h"

namespace zs::light {

namespace {

struct Lane8 {
  using Scalar = double;
  static constexpr int kWidth = 8;
  using Mask = __mmask8;
  __m512d v;
  Lane8() = default;
  explicit Lane8(double x) : v(_mm512_set1_pd(x)) {}
  explicit Lane8(__m512d x) : v(x) {}
  static Lane8 load(const double* p) { return Lane8(_mm512_loadu_pd(p)); }
  void store(double* p) const { _mm512_storeu_pd(p, v); }
  friend Lane8 operator+(Lane8 a, Lane8 b) { return Lane8(_mm512_add_pd(a.v, b.v)); }
  friend Lane8 operator-(Lane8 a, Lane8 b) { return Lane8(_mm512_sub_pd(a.v, b.v)); }
  friend Lane8 operator*(Lane8 a, Lane8 b) { return Lane8(_mm512_mul_pd(a.v, b.v)); }
  friend Lane8 fmadd(Lane8 a, Lane8 b, Lane8 c) { return Lane8(_mm512_fmadd_pd(a.v, b.v, c.v)); }
  friend Lane8 fnmadd(Lane8 a, Lane8 b, Lane8 c) { return Lane8(_mm512_fnmadd_pd(a.v, b.v, c.v)); }
  friend Lane8 operator/(Lane8 a, Lane8 b) { return Lane8(_mm512_div_pd(a.v, b.v)); }
  friend __mmask8 operator<(Lane8 a, Lane8 b) { return _mm512_cmp_pd_mask(a.v, b.v, _CMP_LT_OQ); }
  friend __mmask8 operator>(Lane8 a, Lane8 b) { return _mm512_cmp_pd_mask(a.v, b.v, _CMP_GT_OQ); }
  friend __mmask8 operator<=(Lane8 a, Lane8 b) { return _mm512_cmp_pd_mask(a.v, b.v, _CMP_LE_OQ); }
  friend __mmask8 operator>=(Lane8 a, Lane8 b) { return _mm512_cmp_pd_mask(a.v, b.v, _CMP_GE_OQ); }
  friend __mmask8 operator==(Lane8 a, Lane8 b) { return _mm512_cmp_pd_mask(a.v, b.v, _CMP_EQ_OQ); }
  friend __mmask8 not_less(Lane8 a, Lane8 b) { return _mm512_cmp_pd_mask(a.v, b.v, _CMP_NLT_UQ); }
  static __mmask8 mask_and(__mmask8 a, __mmask8 b) { return __mmask8(a & b); }
  static bool all(__mmask8 m) { return m == 0xFF; }
  static void store_mask(uint8_t* p, __mmask8 m) {
    for (int l = 0; l < 8; ++l) p[l] = uint8_t((m >> l) & 1);
  }
  // table[n] per lane: one permute from a register when the table has at
  // most 8 entries (the index is read from n + 2^52's low mantissa bits),
  // a gather otherwise.
  static Lane8 lookup(const double* table, Lane8 n, int entries) {
    if (entries <= 8) {
      const __m512i idx = _mm512_castpd_si512(_mm512_add_pd(n.v, _mm512_set1_pd(4503599627370496.0)));
      return Lane8(_mm512_permutexvar_pd(idx, _mm512_loadu_pd(table)));
    }
    return Lane8(_mm512_i32gather_pd(_mm512_cvttpd_epi32(n.v), table, 8));
  }
  // vmaxpd returns its second operand unless the first is greater: as Lane1.
  friend Lane8 max(Lane8 a, Lane8 b) { return Lane8(_mm512_max_pd(a.v, b.v)); }
  friend Lane8 abs(Lane8 a) {
    return Lane8(_mm512_castsi512_pd(
        _mm512_and_si512(_mm512_castpd_si512(a.v), _mm512_set1_epi64(0x7fffffffffffffffLL))));
  }
  friend Lane8 select(__mmask8 m, Lane8 a, Lane8 b) { return Lane8(_mm512_mask_blend_pd(m, b.v, a.v)); }
  friend Lane8 round_int(Lane8 x) {
    const __m512d c = _mm512_set1_pd(6755399441055744.0);
    return Lane8(_mm512_sub_pd(_mm512_add_pd(x.v, c), c));
  }
  friend Lane8 pow2_int(Lane8 n) {
    const __m512d t = _mm512_add_pd(n.v, _mm512_set1_pd(4503599627370496.0 + 1023.0));
    const __m512i k = _mm512_and_si512(_mm512_castpd_si512(t), _mm512_set1_epi64(0x000fffffffffffffLL));
    return Lane8(_mm512_castsi512_pd(_mm512_slli_epi64(k, 52)));
  }
  friend void split_exponent(Lane8 w, Lane8* e, Lane8* m) {
    const __m512i u = _mm512_castpd_si512(w.v);
    const __m512i eb = _mm512_or_si512(_mm512_srli_epi64(u, 52), _mm512_set1_epi64(0x4330000000000000LL));
    e->v = _mm512_sub_pd(_mm512_castsi512_pd(eb), _mm512_set1_pd(4503599627370496.0 + 1023.0));
    const __m512i mb = _mm512_or_si512(_mm512_and_si512(u, _mm512_set1_epi64(0x000fffffffffffffLL)),
                                       _mm512_set1_epi64(0x3ff0000000000000LL));
    m->v = _mm512_castsi512_pd(mb);
  }
};

using Lane8x2 = LanePair<Lane8>;  // 16 segments per step

}  // namespace

void segment_lights_avx512(const TfTables& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts) {
  if (parts > 0) {
    for (size_t i = 0; i < n; i += 8) segment_light_split<Lane8>(tf, q, i, inv_unit, parts);
    return;
  }
  size_t i = 0;
  for (; i + 16 <= n; i += 16) segment_light<Lane8x2>(tf, q, i, inv_unit);
  for (; i < n; i += 8) segment_light<Lane8>(tf, q, i, inv_unit);
}

}  // namespace zs::light
