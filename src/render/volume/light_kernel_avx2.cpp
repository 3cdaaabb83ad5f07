// light_kernel.h on four doubles per lane (AVX2), and on eight floats (the
// single-precision kernel). This file alone is
// compiled with -mavx2 -mfma and includes nothing but the kernel, so no inline
// function compiled for AVX2 can leak into code that runs without it.
#include <immintrin.h>

#include "base/optics/lane_pair.h"
#include "base/optics/light_kernel.h"

namespace zs::light {

namespace {

struct Lane4 {
  using Scalar = double;
  static constexpr int kWidth = 4;
  using Mask = __m256d;
  __m256d v;
  Lane4() = default;
  explicit Lane4(double x) : v(_mm256_set1_pd(x)) {}
  explicit Lane4(__m256d x) : v(x) {}
  static Lane4 load(const double* p) { return Lane4(_mm256_loadu_pd(p)); }
  void store(double* p) const { _mm256_storeu_pd(p, v); }
  friend Lane4 operator+(Lane4 a, Lane4 b) { return Lane4(_mm256_add_pd(a.v, b.v)); }
  friend Lane4 operator-(Lane4 a, Lane4 b) { return Lane4(_mm256_sub_pd(a.v, b.v)); }
  friend Lane4 operator*(Lane4 a, Lane4 b) { return Lane4(_mm256_mul_pd(a.v, b.v)); }
  friend Lane4 operator/(Lane4 a, Lane4 b) { return Lane4(_mm256_div_pd(a.v, b.v)); }
  friend Lane4 fmadd(Lane4 a, Lane4 b, Lane4 c) { return Lane4(_mm256_fmadd_pd(a.v, b.v, c.v)); }
  friend Lane4 fnmadd(Lane4 a, Lane4 b, Lane4 c) { return Lane4(_mm256_fnmadd_pd(a.v, b.v, c.v)); }
  friend __m256d operator<(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ); }
  friend __m256d operator>(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ); }
  friend __m256d operator<=(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_LE_OQ); }
  friend __m256d operator>=(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_GE_OQ); }
  friend __m256d operator==(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_EQ_OQ); }
  friend __m256d not_less(Lane4 a, Lane4 b) { return _mm256_cmp_pd(a.v, b.v, _CMP_NLT_UQ); }
  static __m256d mask_and(__m256d a, __m256d b) { return _mm256_and_pd(a, b); }
  static bool all(__m256d m) { return _mm256_movemask_pd(m) == 15; }
  static void store_mask(uint8_t* p, __m256d m) {
    // Lane l's bit to byte l (the shifted copies do not overlap), one store.
    const uint32_t bytes = (uint32_t(_mm256_movemask_pd(m)) * 0x204081u) & 0x01010101u;
    std::memcpy(p, &bytes, 4);
  }
  // table[n] per lane; n holds integers in [0, entries). Tables of at most
  // 4 entries are permuted from one register, of at most 8 from two (a
  // double is a pair of 32-bit halves for vpermps), longer ones gathered.
  static Lane4 lookup(const double* table, Lane4 n, int entries) {
    const __m128i i32 = _mm256_cvttpd_epi32(n.v);
    if (entries <= 8) {
      const __m256i i64 = _mm256_cvtepu32_epi64(i32);
      const __m256i lo = _mm256_slli_epi64(_mm256_and_si256(i64, _mm256_set1_epi64x(3)), 1);
      const __m256i pair = _mm256_or_si256(lo, _mm256_slli_epi64(_mm256_add_epi64(lo, _mm256_set1_epi64x(1)), 32));
      const __m256 a = _mm256_permutevar8x32_ps(_mm256_castpd_ps(_mm256_loadu_pd(table)), pair);
      if (entries <= 4) return Lane4(_mm256_castps_pd(a));
      const __m256 b = _mm256_permutevar8x32_ps(_mm256_castpd_ps(_mm256_loadu_pd(table + 4)), pair);
      const __m256d high = _mm256_castsi256_pd(_mm256_cmpgt_epi64(i64, _mm256_set1_epi64x(3)));
      return Lane4(_mm256_blendv_pd(_mm256_castps_pd(a), _mm256_castps_pd(b), high));
    }
    return Lane4(_mm256_mask_i32gather_pd(_mm256_setzero_pd(), table, i32, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8));
  }
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

using Lane4x2 = LanePair<Lane4>;  // 8 segments per step

// Eight floats: the single-precision kernel. The batch holds doubles; loads
// and stores convert (round to nearest, as Lane1f's do).
struct Lane8f {
  using Scalar = float;
  static constexpr int kWidth = 8;
  using Mask = __m256;
  __m256 v;
  Lane8f() = default;
  explicit Lane8f(double x) : v(_mm256_set1_ps(float(x))) {}
  explicit Lane8f(__m256 x) : v(x) {}
  static Lane8f load(const double* p) {
    return Lane8f(_mm256_set_m128(_mm256_cvtpd_ps(_mm256_loadu_pd(p + 4)), _mm256_cvtpd_ps(_mm256_loadu_pd(p))));
  }
  void store(double* p) const {
    _mm256_storeu_pd(p, _mm256_cvtps_pd(_mm256_castps256_ps128(v)));
    _mm256_storeu_pd(p + 4, _mm256_cvtps_pd(_mm256_extractf128_ps(v, 1)));
  }
  friend Lane8f operator+(Lane8f a, Lane8f b) { return Lane8f(_mm256_add_ps(a.v, b.v)); }
  friend Lane8f operator-(Lane8f a, Lane8f b) { return Lane8f(_mm256_sub_ps(a.v, b.v)); }
  friend Lane8f operator*(Lane8f a, Lane8f b) { return Lane8f(_mm256_mul_ps(a.v, b.v)); }
  friend Lane8f operator/(Lane8f a, Lane8f b) { return Lane8f(_mm256_div_ps(a.v, b.v)); }
  friend Lane8f fmadd(Lane8f a, Lane8f b, Lane8f c) { return Lane8f(_mm256_fmadd_ps(a.v, b.v, c.v)); }
  friend Lane8f fnmadd(Lane8f a, Lane8f b, Lane8f c) { return Lane8f(_mm256_fnmadd_ps(a.v, b.v, c.v)); }
  friend __m256 operator<(Lane8f a, Lane8f b) { return _mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ); }
  friend __m256 operator>(Lane8f a, Lane8f b) { return _mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ); }
  friend __m256 operator<=(Lane8f a, Lane8f b) { return _mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ); }
  friend __m256 operator>=(Lane8f a, Lane8f b) { return _mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ); }
  friend __m256 operator==(Lane8f a, Lane8f b) { return _mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ); }
  friend __m256 not_less(Lane8f a, Lane8f b) { return _mm256_cmp_ps(a.v, b.v, _CMP_NLT_UQ); }
  static __m256 mask_and(__m256 a, __m256 b) { return _mm256_and_ps(a, b); }
  static bool all(__m256 m) { return _mm256_movemask_ps(m) == 255; }
  static void store_mask(uint8_t* p, __m256 m) {
    // Four lanes' bits to four bytes at a time (as Lane4::store_mask).
    const uint32_t bits = uint32_t(_mm256_movemask_ps(m));
    const uint32_t lo = ((bits & 15u) * 0x204081u) & 0x01010101u, hi = ((bits >> 4) * 0x204081u) & 0x01010101u;
    std::memcpy(p, &lo, 4);
    std::memcpy(p + 4, &hi, 4);
  }
  // table[n] per lane: one permute for tables of at most 8 entries, else a gather.
  static Lane8f lookup(const float* table, Lane8f n, int entries) {
    const __m256i i32 = _mm256_cvttps_epi32(n.v);
    if (entries <= 8) return Lane8f(_mm256_permutevar8x32_ps(_mm256_loadu_ps(table), i32));
    return Lane8f(_mm256_i32gather_ps(table, i32, 4));
  }
  friend Lane8f max(Lane8f a, Lane8f b) { return Lane8f(_mm256_max_ps(a.v, b.v)); }
  friend Lane8f abs(Lane8f a) {
    return Lane8f(_mm256_castsi256_ps(_mm256_and_si256(_mm256_castps_si256(a.v), _mm256_set1_epi32(0x7fffffff))));
  }
  friend Lane8f select(__m256 m, Lane8f a, Lane8f b) { return Lane8f(_mm256_blendv_ps(b.v, a.v, m)); }
  friend Lane8f round_int(Lane8f x) {
    const __m256 c = _mm256_set1_ps(12582912.0f);  // 1.5·2^23
    return Lane8f(_mm256_sub_ps(_mm256_add_ps(x.v, c), c));
  }
  friend Lane8f pow2_int(Lane8f n) {
    const __m256i k = _mm256_add_epi32(_mm256_cvttps_epi32(n.v), _mm256_set1_epi32(127));
    return Lane8f(_mm256_castsi256_ps(_mm256_slli_epi32(k, 23)));
  }
  friend void split_exponent(Lane8f w, Lane8f* e, Lane8f* m) {
    const __m256i u = _mm256_castps_si256(w.v);
    e->v = _mm256_cvtepi32_ps(_mm256_sub_epi32(_mm256_srli_epi32(u, 23), _mm256_set1_epi32(127)));
    m->v = _mm256_castsi256_ps(
        _mm256_or_si256(_mm256_and_si256(u, _mm256_set1_epi32(0x7fffff)), _mm256_set1_epi32(0x3f800000)));
  }
};

}  // namespace

void segment_lights_avx2(const TfTables& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts) {
  if (parts > 0) {
    for (size_t i = 0; i < n; i += 4) segment_light_split<Lane4>(tf, q, i, inv_unit, parts);
    return;
  }
  for (size_t i = 0; i < n; i += 8) segment_light<Lane4x2>(tf, q, i, inv_unit);  // n: a multiple of 16
}

void segment_lights_avx2_f32(const TfTablesOf<float>& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts) {
  if (parts > 0) {
    for (size_t i = 0; i < n; i += 8) segment_light_split<Lane8f>(tf, q, i, inv_unit, parts);
    return;
  }
  for (size_t i = 0; i < n; i += 16) segment_light<LanePair<Lane8f>>(tf, q, i, inv_unit);  // n: a multiple of 16
}

}  // namespace zs::light
