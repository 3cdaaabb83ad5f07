#include "volume/segment_batch.h"

#include <array>

namespace zs {

namespace light {

void piece_lights_scalar(const PieceArrays& p, size_t n, double inv_unit) {
  for (size_t i = 0; i < n; ++i) {
    PieceIn<Lane1> in;
    for (int k = 0; k < 3; ++k) in.c0[k] = Lane1(p.c0[k][i]), in.c1[k] = Lane1(p.c1[k][i]);
    in.a0 = Lane1(p.a0[i]);
    in.a1 = Lane1(p.a1[i]);
    in.len = Lane1(p.len[i]);
    PieceOut<Lane1> out;
    piece_light(in, inv_unit, &out);
    for (int k = 0; k < 3; ++k) p.rgb[k][i] = out.rgb[k].v;
    p.T[i] = out.T.v;
    p.ok[i] = out.ok;
  }
}

bool have_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

}  // namespace light

SegmentBatch::SegmentBatch(const SegmentIntegrator& integ, const TransferFunction& tf)
    : integ_(integ), tf_(tf), avx2_(light::have_avx2()), pixel_(kCapacity), s0_(kCapacity), s1_(kCapacity),
      len_(kCapacity), buf_(kCapacity * 14), ok_(kCapacity), split_(kCapacity) {
  double* b = buf_.data();
  auto next = [&] {
    double* r = b;
    b += kCapacity;
    return r;
  };
  for (int k = 0; k < 3; ++k) arrays_.c0[k] = next();
  arrays_.a0 = next();
  for (int k = 0; k < 3; ++k) arrays_.c1[k] = next();
  arrays_.a1 = next();
  arrays_.len = next();
  for (int k = 0; k < 3; ++k) arrays_.rgb[k] = next();
  arrays_.T = next();
  arrays_.ok = ok_.data();
}

void SegmentBatch::flush(PixelRecord* px) {
  if (n_ == 0) return;
  const light::PieceArrays& A = arrays_;
  // Colour and opacity at both ends: one piece when both lie in one interval
  // (rgba_in's arithmetic, on the raw tables).
  const double* bs = tf_.breakpoints().data();
  const int nb = int(tf_.breakpoints().size());
  const std::array<double, 4>* at = &tf_.rgba_at_breakpoint(0);
  const double* inv_w = tf_.inverse_widths();
  for (size_t i = 0; i < n_; ++i) {
    const double s0 = s0_[i], s1 = s1_[i];
    const int k0 = tf_.interval(s0), k1 = tf_.interval(s1);
    split_[i] = k0 != k1;
    if (k0 < 0 || k0 + 1 >= nb) {  // clamped: constant outside the points
      const std::array<double, 4>& c = at[k0 < 0 ? 0 : nb - 1];
      for (int k = 0; k < 3; ++k) A.c0[k][i] = A.c1[k][i] = c[size_t(k)];
      A.a0[i] = A.a1[i] = c[3];
    } else {
      const std::array<double, 4>&lo = at[k0], &hi = at[k0 + 1];
      const double t0 = (s0 - bs[k0]) * inv_w[k0], t1 = (s1 - bs[k0]) * inv_w[k0];
      for (int k = 0; k < 3; ++k) {
        const double dv = hi[size_t(k)] - lo[size_t(k)];
        A.c0[k][i] = lo[size_t(k)] + t0 * dv;
        A.c1[k][i] = lo[size_t(k)] + t1 * dv;
      }
      const double da = hi[3] - lo[3];
      A.a0[i] = lo[3] + t0 * da;
      A.a1[i] = lo[3] + t1 * da;
    }
    A.len[i] = len_[i];
  }
  // Pad to a multiple of 4 with empty pieces.
  const size_t n4 = (n_ + 3) & ~size_t(3);
  for (size_t i = n_; i < n4; ++i) {
    for (int k = 0; k < 3; ++k) A.c0[k][i] = A.c1[k][i] = 0;
    A.a0[i] = A.a1[i] = A.len[i] = 0;
  }
  const double inv_unit = 1.0 / tf_.unit_distance();
  if (avx2_) light::piece_lights_avx2(A, n4, inv_unit);
  else light::piece_lights_scalar(A, n4, inv_unit);
  for (size_t i = 0; i < n_; ++i) {
    double rgb[3], T;
    if (split_[i] || !A.ok[i]) {
      const SegmentLight l = integ_.integrate(s0_[i], s1_[i], len_[i]);
      rgb[0] = l.rgb[0], rgb[1] = l.rgb[1], rgb[2] = l.rgb[2], T = l.T;
    } else {
      rgb[0] = A.rgb[0][i], rgb[1] = A.rgb[1][i], rgb[2] = A.rgb[2][i], T = A.T[i];
    }
    PixelRecord& p = px[pixel_[i]];
    const double Tp = p.T;
    p.rgb[0] += Tp * rgb[0];
    p.rgb[1] += Tp * rgb[1];
    p.rgb[2] += Tp * rgb[2];
    p.T = Tp * T;
  }
  n_ = 0;
}

}  // namespace zs
