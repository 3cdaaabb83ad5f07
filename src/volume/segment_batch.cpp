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
  // Local copies of every pointer: stores through uint8_t may alias anything,
  // and would otherwise make the compiler reload each pointer per element.
  double *c00 = A.c0[0], *c01 = A.c0[1], *c02 = A.c0[2], *c10 = A.c1[0], *c11 = A.c1[1], *c12 = A.c1[2];
  double *a0 = A.a0, *a1 = A.a1, *len = A.len;
  const double *S0 = s0_.data(), *S1 = s1_.data(), *LEN = len_.data();
  uint8_t* split = split_.data();
  for (size_t i = 0; i < n_; ++i) {
    const double s0 = S0[i], s1 = S1[i];
    const int k0 = tf_.interval(s0), k1 = tf_.interval(s1);
    split[i] = k0 != k1;
    if (k0 < 0 || k0 + 1 >= nb) {  // clamped: constant outside the points
      const std::array<double, 4>& c = at[k0 < 0 ? 0 : nb - 1];
      c00[i] = c10[i] = c[0];
      c01[i] = c11[i] = c[1];
      c02[i] = c12[i] = c[2];
      a0[i] = a1[i] = c[3];
    } else {
      const std::array<double, 4>&lo = at[k0], &hi = at[k0 + 1];
      const double t0 = (s0 - bs[k0]) * inv_w[k0], t1 = (s1 - bs[k0]) * inv_w[k0];
      const double d0 = hi[0] - lo[0], d1 = hi[1] - lo[1], d2 = hi[2] - lo[2], d3 = hi[3] - lo[3];
      c00[i] = lo[0] + t0 * d0;
      c10[i] = lo[0] + t1 * d0;
      c01[i] = lo[1] + t0 * d1;
      c11[i] = lo[1] + t1 * d1;
      c02[i] = lo[2] + t0 * d2;
      c12[i] = lo[2] + t1 * d2;
      a0[i] = lo[3] + t0 * d3;
      a1[i] = lo[3] + t1 * d3;
    }
    len[i] = LEN[i];
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
  const double *R = A.rgb[0], *G = A.rgb[1], *B = A.rgb[2], *TT = A.T;
  const uint8_t* ok = A.ok;
  const uint32_t* pix = pixel_.data();
  for (size_t i = 0; i < n_; ++i) {
    double r, g, b, T;
    if (split[i] || !ok[i]) {
      const SegmentLight l = integ_.integrate(S0[i], S1[i], LEN[i]);
      r = l.rgb[0], g = l.rgb[1], b = l.rgb[2], T = l.T;
    } else {
      r = R[i], g = G[i], b = B[i], T = TT[i];
    }
    PixelRecord& p = px[pix[i]];
    const double Tp = p.T;
    p.rgb[0] += Tp * r;
    p.rgb[1] += Tp * g;
    p.rgb[2] += Tp * b;
    p.T = Tp * T;
  }
  n_ = 0;
}

}  // namespace zs
