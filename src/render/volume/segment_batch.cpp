#include "render/volume/segment_batch.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace zs {

namespace light {

void segment_lights_scalar(const TfTables& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts) {
  for (size_t i = 0; i < n; ++i) {
    if (parts > 0) segment_light_split<Lane1>(tf, q, i, inv_unit, parts);
    else segment_light<Lane1>(tf, q, i, inv_unit);
  }
}

void segment_lights_scalar_f32(const TfTablesOf<float>& tf, const SegmentSoA& q, size_t n, double inv_unit, int parts) {
  for (size_t i = 0; i < n; ++i) {
    if (parts > 0) segment_light_split<Lane1f>(tf, q, i, inv_unit, parts);
    else segment_light<Lane1f>(tf, q, i, inv_unit);
  }
}

bool have_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

bool have_avx512() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx512f");
#else
  return false;
#endif
}

}  // namespace light

namespace {

// Points tf into 11 tables of m entries each, laid out as the constructor
// fills them: 0 left, 1 inv_w, 2..5 lo, 6..9 d, 10 cut.
template <class T>
void point_tables(light::TfTablesOf<T>* tf, int nb, const T* bs, const T* t, size_t m) {
  auto table = [&](int i) { return t + size_t(i) * m; };
  tf->nb = nb;
  tf->bs = bs;
  tf->cut = table(10);
  tf->left = table(0);
  tf->inv_w = table(1);
  for (int c = 0; c < 4; ++c) {
    tf->lo[c] = table(2 + c);
    tf->d[c] = table(6 + c);
  }
}

}  // namespace

KernelWidth best_kernel_width() {
  KernelWidth w = light::have_avx512() ? KernelWidth::AVX512 : light::have_avx2() ? KernelWidth::AVX2 : KernelWidth::Scalar;
  if (const char* cap = std::getenv("ZSWEEP_KERNEL")) {
    if (!std::strcmp(cap, "scalar")) w = KernelWidth::Scalar;
    else if (!std::strcmp(cap, "avx2") && w == KernelWidth::AVX512) w = KernelWidth::AVX2;
  }
  return w;
}

const char* kernel_name(KernelWidth width, KernelPrecision precision) {
  if (width == KernelWidth::AVX512 && !light::have_avx512()) width = KernelWidth::AVX2;
  if (width != KernelWidth::Scalar && !light::have_avx2()) width = KernelWidth::Scalar;
  if (precision == KernelPrecision::Single) return width == KernelWidth::Scalar ? "scalar-f32" : "avx2-f32";
  return width == KernelWidth::AVX512 ? "avx512" : width == KernelWidth::AVX2 ? "avx2" : "scalar";
}

SegmentBatch::SegmentBatch(const SegmentIntegrator& integ, const TransferFunction& tf, KernelWidth width,
                           KernelPrecision precision)
    : integ_(integ), tf_(tf), width_(width), precision_(precision), pixel_(kCapacity), s0_(kCapacity), s1_(kCapacity), len_(kCapacity),
      ok_(kCapacity), retry_(kCapacity), r_s0_(kCapacity), r_s1_(kCapacity), r_len_(kCapacity), r_T_(kCapacity),
      r_ok_(kCapacity), inv_unit_(1.0 / tf.unit_distance()) {
  if (width_ == KernelWidth::AVX512 && !light::have_avx512()) width_ = KernelWidth::AVX2;
  if (width_ == KernelWidth::AVX2 && !light::have_avx2()) width_ = KernelWidth::Scalar;
  if (precision_ == KernelPrecision::Single && !light::have_avx2()) width_ = KernelWidth::Scalar;
  for (int k = 0; k < 3; ++k) rgb_[k].resize(kCapacity), r_rgb_[k].resize(kCapacity);
  T_.resize(kCapacity);
  const std::vector<double>& bs = tf.breakpoints();
  const int nb = int(bs.size());
  if (nb > light::kCountInKernel) {
    n0_.resize(kCapacity);
    n1_.resize(kCapacity);
  }
  // Tables indexed by n = k + 1 (light_kernel.h), at least 8 entries each.
  const size_t m = std::max<size_t>(size_t(nb) + 1, 8);
  tables_.assign(m * 11, 0.0);
  double* t = tables_.data();
  auto table = [&](int i) { return t + size_t(i) * m; };
  for (int n = 0; n <= nb; ++n) {
    const int k = n - 1;
    const bool inside = k >= 0 && k + 1 < nb;
    const std::array<double, 4>& lo = tf.rgba_at_breakpoint(k < 0 ? 0 : inside ? k : nb - 1);
    table(0)[n] = inside ? bs[size_t(k)] : 0.0;
    table(1)[n] = inside ? tf.inverse_widths()[k] : 0.0;
    table(10)[n] = n >= 1 ? bs[size_t(n - 1)] : 0.0;
    for (int c = 0; c < 4; ++c) {
      table(2 + c)[n] = lo[size_t(c)];
      table(6 + c)[n] = inside ? tf.rgba_at_breakpoint(k + 1)[size_t(c)] - lo[size_t(c)] : 0.0;
    }
  }
  point_tables(&tf_tables_, nb, bs.data(), t, m);
  double max_dc = 0;  // a one-interval piece's |c1 - c0| is at most its interval's |d|
  for (int c = 0; c < 3; ++c)
    for (int n = 0; n <= nb; ++n) max_dc = std::max(max_dc, std::abs(table(6 + c)[n]));
  tf_tables_.thin = light::hermite8_thin_limit(max_dc);
  // Single precision: the same tables rounded to float, the looser tolerance.
  // Scalars and breakpoints are taken relative to the middle of the transfer
  // function's range (in double, then rounded), so a range far from zero
  // (300–310 K, say) keeps a float's resolution of its width, not of |s|.
  s_ref_ = 0.5 * (bs.front() + bs.back());
  tables_f_.assign(tables_.begin(), tables_.end());
  for (int n = 0; n <= nb; ++n) {
    const int k = n - 1;
    if (k >= 0 && k + 1 < nb) tables_f_[size_t(n)] = float(bs[size_t(k)] - s_ref_);  // left
    if (n >= 1) tables_f_[10 * m + size_t(n)] = float(bs[size_t(n - 1)] - s_ref_);   // cut
  }
  bs_f_.resize(bs.size());
  for (size_t j = 0; j < bs.size(); ++j) bs_f_[j] = float(bs[j] - s_ref_);
  sh0_.resize(kCapacity);
  sh1_.resize(kCapacity);
  point_tables(&tf_tables_f_, nb, bs_f_.data(), tables_f_.data(), m);
  tf_tables_f_.tolerance = light::kSingleTolerance;
  tf_tables_f_.thin = light::hermite8_thin_limit(max_dc, light::kSingleTolerance);
}

void SegmentBatch::run_kernel() {
  run_pass(s0_.data(), s1_.data(), len_.data(), n_, rgb_[0].data(), rgb_[1].data(), rgb_[2].data(), T_.data(),
           ok_.data(), 0);
  // Segments the one-piece rule could not take (a breakpoint inside, or a
  // thick piece): again, in pieces, with the vector kernel; what still fails
  // goes to SegmentIntegrator in flush().
  // Nearly every segment is ok: skip eight flags at a time (ok_ holds
  // kCapacity entries, a multiple of 8; those past n_ are never read).
  size_t m = 0;
  for (size_t i0 = 0; i0 < n_; i0 += 8) {
    uint64_t flags;
    std::memcpy(&flags, ok_.data() + i0, 8);
    if (flags == 0x0101010101010101ull) continue;
    for (size_t i = i0; i < std::min(n_, i0 + 8); ++i)
      if (!ok_[i]) {
        retry_[m] = uint32_t(i);
        r_s0_[m] = s0_[i];
        r_s1_[m] = s1_[i];
        r_len_[m] = len_[i];
        ++m;
      }
  }
  if (m == 0) return;
  run_pass(r_s0_.data(), r_s1_.data(), r_len_.data(), m, r_rgb_[0].data(), r_rgb_[1].data(), r_rgb_[2].data(),
           r_T_.data(), r_ok_.data(), kSplitParts);
  for (size_t r = 0; r < m; ++r) {
    if (!r_ok_[r]) continue;
    const uint32_t i = retry_[r];
    for (int k = 0; k < 3; ++k) rgb_[k][i] = r_rgb_[k][r];
    T_[i] = r_T_[r];
    ok_[i] = 1;
  }
}

void SegmentBatch::run_pass(double* s0, double* s1, double* len, size_t n, double* r, double* g, double* b,
                            double* T, uint8_t* ok, int parts) {
  // Pad to a multiple of 16 with empty segments.
  const size_t n16 = (n + 15) & ~size_t(15);
  const double s_pad = tf_.breakpoints().front();
  for (size_t i = n; i < n16; ++i) s0[i] = s1[i] = s_pad, len[i] = 0;
  light::SegmentSoA q{s0, s1, len, nullptr, nullptr, {r, g, b}, T, ok};
  if (!n0_.empty()) {  // long transfer functions: search here, not in the kernel
    for (size_t i = 0; i < n16; ++i) {
      n0_[i] = double(tf_.interval(s0[i]) + 1);
      n1_[i] = double(tf_.interval(s1[i]) + 1);
    }
    q.n0 = n0_.data();
    q.n1 = n1_.data();
  }
  if (precision_ == KernelPrecision::Single) {
    for (size_t i = 0; i < n16; ++i) sh0_[i] = s0[i] - s_ref_, sh1_[i] = s1[i] - s_ref_;
    q.s0 = sh0_.data();
    q.s1 = sh1_.data();
    // Every AVX-512 CPU has AVX2: eight floats per vector either way.
    if (width_ != KernelWidth::Scalar) light::segment_lights_avx2_f32(tf_tables_f_, q, n16, inv_unit_, parts);
    else light::segment_lights_scalar_f32(tf_tables_f_, q, n16, inv_unit_, parts);
    return;
  }
  switch (width_) {
    case KernelWidth::AVX512: light::segment_lights_avx512(tf_tables_, q, n16, inv_unit_, parts); break;
    case KernelWidth::AVX2: light::segment_lights_avx2(tf_tables_, q, n16, inv_unit_, parts); break;
    case KernelWidth::Scalar: light::segment_lights_scalar(tf_tables_, q, n16, inv_unit_, parts); break;
  }
}

void SegmentBatch::flush(PixelLight* light) {
  if (n_ == 0) return;
  run_kernel();
  const double *R = rgb_[0].data(), *G = rgb_[1].data(), *B = rgb_[2].data(), *TT = T_.data();
  const uint8_t* ok = ok_.data();
  const uint32_t* pix = pixel_.data();
  for (size_t i = 0; i < n_; ++i) {
    double r = R[i], g = G[i], b = B[i], T = TT[i];
    if (!ok[i]) {
      const SegmentLight l = integ_.integrate(s0_[i], s1_[i], len_[i]);
      r = l.rgb[0], g = l.rgb[1], b = l.rgb[2], T = l.T;
    }
    PixelLight& p = light[pix[i]];
    const double Tp = p.T;
    p.rgb[0] += Tp * r;
    p.rgb[1] += Tp * g;
    p.rgb[2] += Tp * b;
    p.T = Tp * T;
  }
  n_ = 0;
}

void SegmentBatch::integrate(std::vector<SegmentLight>* out) {
  out->clear();
  if (n_ == 0) return;
  run_kernel();
  for (size_t i = 0; i < n_; ++i) {
    if (!ok_[i]) out->push_back(integ_.integrate(s0_[i], s1_[i], len_[i]));
    else out->push_back({{rgb_[0][i], rgb_[1][i], rgb_[2][i]}, T_[i]});
  }
  n_ = 0;
}

}  // namespace zs
