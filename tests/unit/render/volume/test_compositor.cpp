// Compositor on hand-made pixel lists: a constant cell against the closed
// form of absorption plus emission (T = exp(-tau L), I = c (1 - T), tau =
// -ln(1 - a)/unit), front-to-back composition of consecutive segments, the
// inside count (gaps outside the mesh, seams), early termination, z_limit,
// and the batched path against the unbatched one.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "base/optics/transfer_function.h"
#include "base/view/camera.h"
#include "render/volume/compositor.h"
#include "render/volume/pixel_lists.h"
#include "render/volume/segment_batch.h"
#include "base/optics/segment_integrator.h"

namespace zs {
namespace {

TransferFunction constant_tf(const double c[3], double a, double unit) {
  return TransferFunction({{0, c[0], c[1], c[2]}, {1, c[0], c[1], c[2]}}, {{0, a}, {1, a}}, unit);
}

// A tile of `n` pixels: records, lights, lists, and a compositor over them.
struct Tile {
  std::vector<PixelRecord> px;
  std::vector<PixelLight> light;
  PixelLists lists;
  Tile(size_t n, size_t max_overflow = 1 << 16) : px(n), light(n) {
    for (auto& p : px) p.reset();
    for (auto& l : light) l.reset();
    lists.reset(max_overflow);
  }
  void add(size_t pixel, float z, float s, uint32_t kind) {
    ASSERT_TRUE(lists.insert(px[pixel], z, s, kind));
    lists.add_live(1);
  }
};

const View& ortho_view() {
  static const View v(Camera{}, 8, 8);
  return v;
}

TEST(Compositor, ConstantCellMatchesClosedForm) {
  const double c[3] = {0.2, 0.5, 0.9};
  for (bool batched : {false, true})
    for (double a : {0.01, 0.3, 0.9, 0.999})
      for (double unit : {0.5, 1.0, 3.0})
        for (float L : {0.125f, 1.0f, 2.5f, 16.0f}) {
          const TransferFunction tf = constant_tf(c, a, unit);
          const SegmentIntegrator integ(tf, Integrator::Exact);
          std::unique_ptr<SegmentBatch> batch;
          if (batched) batch = std::make_unique<SegmentBatch>(integ, tf);
          Tile t(1);
          Compositor comp(ortho_view(), integ, 0.0, batch.get(), t.px.data(), t.light.data());
          ASSERT_EQ(comp.batched(), batched);
          const float z0 = 0.75f;
          t.add(0, z0, 0.5f, kEntry);
          t.add(0, z0 + L, 0.5f, kExit);
          comp.composite(t.px[0], t.lists, INFINITY, 3, 4);
          comp.flush();
          const double tau = -std::log(1 - a) / unit;
          const double T = std::exp(-tau * L);
          const PixelLight& l = t.light[0];
          EXPECT_NEAR(l.T, T, 1e-12) << a << " " << unit << " " << L;
          for (int k = 0; k < 3; ++k) EXPECT_NEAR(l.rgb[k], c[k] * (1 - T), 1e-12) << a << " " << unit << " " << L;
          EXPECT_EQ(comp.segments(), 1u);
          EXPECT_EQ(comp.terminated_pixels(), 0u);
          EXPECT_EQ(t.px[0].pending(), 0u);
          EXPECT_EQ(t.px[0].inside, 0);
          EXPECT_EQ(t.px[0].last_z, z0 + L);
          EXPECT_EQ(t.lists.live_fragments(), 0u);
        }
}

TEST(Compositor, PerspectiveSegmentsAreLongerByTheRayFactor) {
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.fov_y = 60;
  const View view(cam, 16, 16);
  const double c[3] = {1.0, 0.25, 0.0};
  const double a = 0.4;
  const TransferFunction tf = constant_tf(c, a, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  for (bool batched : {false, true}) {
    std::unique_ptr<SegmentBatch> batch;
    if (batched) batch = std::make_unique<SegmentBatch>(integ, tf);
    Tile t(1);
    Compositor comp(view, integ, 0.0, batch.get(), t.px.data(), t.light.data());
    t.add(0, 2.0f, 0.5f, kEntry);
    t.add(0, 3.5f, 0.5f, kExit);
    comp.composite(t.px[0], t.lists, INFINITY, 0, 15);  // a corner: factor well above 1
    comp.flush();
    const double f = view.ray_length_factor(0, 15);
    ASSERT_GT(f, 1.1);
    const double T = std::exp(std::log(1 - a) * 1.5 * f);
    EXPECT_NEAR(t.light[0].T, T, 1e-12);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(t.light[0].rgb[k], c[k] * (1 - T), 1e-12);
  }
}

// Two cells of different constant colour and opacity (scalars 0 and 1 of
// a two-point TF): front-to-back I = I1 + T1 I2, T = T1 T2, whether they
// share a face (the exit and the entry at the same depth, inserted in
// either order) or are separated by a gap outside the mesh.
TEST(Compositor, ConsecutiveSegmentsComposeFrontToBack) {
  const double c1[3] = {0.9, 0.1, 0.3}, c2[3] = {0.05, 0.7, 1.0};
  const double a1 = 0.35, a2 = 0.8, unit = 2.0;
  const TransferFunction tf({{0, c1[0], c1[1], c1[2]}, {1, c2[0], c2[1], c2[2]}}, {{0, a1}, {1, a2}}, unit);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  const float L1 = 1.5f, L2 = 0.75f;
  const double T1 = std::pow(1 - a1, L1 / unit), T2 = std::pow(1 - a2, L2 / unit);
  for (bool batched : {false, true})
    for (int variant = 0; variant < 3; ++variant) {
      std::unique_ptr<SegmentBatch> batch;
      if (batched) batch = std::make_unique<SegmentBatch>(integ, tf);
      Tile t(2);
      Compositor comp(ortho_view(), integ, 0.0, batch.get(), t.px.data(), t.light.data());
      const float z0 = 1.0f, gap = variant == 2 ? 4.0f : 0.0f;
      t.add(1, z0, 0.f, kEntry);
      if (variant == 1) {  // the entry of cell 2 inserted before the exit of cell 1
        t.add(1, z0 + L1 + gap, 1.f, kEntry);
        t.add(1, z0 + L1, 0.f, kExit);
      } else {
        t.add(1, z0 + L1, 0.f, kExit);
        t.add(1, z0 + L1 + gap, 1.f, kEntry);
      }
      t.add(1, z0 + L1 + gap + L2, 1.f, kExit);
      comp.composite(t.px[1], t.lists, INFINITY, 1, 0);
      comp.flush();
      const PixelLight& l = t.light[1];
      EXPECT_NEAR(l.T, T1 * T2, 1e-12) << variant;
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(l.rgb[k], c1[k] * (1 - T1) + T1 * c2[k] * (1 - T2), 1e-12) << variant << " " << k;
      EXPECT_EQ(comp.segments(), 2u) << variant;  // no zero-length seam, no gap segment
      // The other pixel was never touched.
      EXPECT_EQ(t.light[0].T, 1.0);
      EXPECT_EQ(t.light[0].rgb[0], 0.0);
    }
}

TEST(Compositor, StepPastCountsEntriesAndExitsWithoutGoingNegative) {
  PixelRecord px;
  px.reset();
  Compositor::step_past(px, 1.f, 2.f, kExit);  // an exit with no entry (grazing ray)
  EXPECT_EQ(px.inside, 0);
  EXPECT_EQ(px.last_z, 1.f);
  EXPECT_EQ(px.last_s, 2.f);
  Compositor::step_past(px, 2.f, 3.f, kEntry);
  Compositor::step_past(px, 3.f, 4.f, kEntry);
  EXPECT_EQ(px.inside, 2);
  Compositor::step_past(px, 4.f, 5.f, kInterior);
  EXPECT_EQ(px.inside, 2);
  Compositor::step_past(px, 5.f, 6.f, kExit);
  EXPECT_EQ(px.inside, 1);
  EXPECT_EQ(px.last_z, 5.f);
  EXPECT_EQ(px.last_s, 6.f);
  px.inside = INT16_MAX;
  Compositor::step_past(px, 6.f, 0.f, kEntry);
  EXPECT_EQ(px.inside, INT16_MAX);  // saturates
}

TEST(Compositor, UnmatchedExitStartsNothing) {
  // exit, entry, exit: only the segment between the entry and the last exit.
  const double c[3] = {0.5, 0.5, 0.5};
  const TransferFunction tf = constant_tf(c, 0.5, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  Tile t(1);
  Compositor comp(ortho_view(), integ, 0.0, nullptr, t.px.data(), t.light.data());
  t.add(0, 1.f, 0.5f, kExit);
  t.add(0, 3.f, 0.5f, kEntry);
  t.add(0, 4.f, 0.5f, kExit);
  comp.composite(t.px[0], t.lists, INFINITY, 0, 0);
  EXPECT_EQ(comp.segments(), 1u);
  EXPECT_NEAR(t.light[0].T, 0.5, 1e-14);
  EXPECT_NEAR(t.light[0].rgb[0], 0.25, 1e-14);
}

TEST(Compositor, EarlyTerminationStopsThePixel) {
  // Opacity 0.3 per unit: each unit segment multiplies T by 0.7. With the
  // renderer's threshold t/510 the pixel stops after the first segment that
  // takes T below it: t = 255 (0.5): 2 segments (0.49); 200 (0.392): 3
  // (0.343); 100 (0.196): 5 (0.168).
  const double c[3] = {0.3, 0.6, 0.9};
  const TransferFunction tf = constant_tf(c, 0.3, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  const struct {
    int t;
    unsigned segments;
  } cases[] = {{255, 2}, {200, 3}, {100, 5}};
  for (const auto& cs : cases) {
    Tile t(1);
    Compositor comp(ortho_view(), integ, cs.t / 510.0, nullptr, t.px.data(), t.light.data());
    t.add(0, 0.f, 0.5f, kEntry);
    for (int i = 1; i < 8; ++i) t.add(0, float(i), 0.5f, kInterior);  // 4 inline, 4 in the overflow
    t.add(0, 8.f, 0.5f, kExit);
    comp.composite(t.px[0], t.lists, INFINITY, 0, 0);
    const double T = std::pow(0.7, cs.segments);
    EXPECT_EQ(comp.segments(), cs.segments) << cs.t;
    EXPECT_EQ(comp.terminated_pixels(), 1u);
    EXPECT_EQ(t.px[0].done, 1);
    EXPECT_LT(t.light[0].T, cs.t / 510.0);
    EXPECT_NEAR(t.light[0].T, T, 1e-12);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(t.light[0].rgb[k], c[k] * (1 - T), 1e-12);
    // Everything behind was freed.
    EXPECT_EQ(t.px[0].pending(), 0u);
    EXPECT_EQ(t.lists.live_fragments(), 0u);
    EXPECT_EQ(t.lists.overflow_fragments(), 0u);
    // Later fragments of a done pixel are dropped without touching its light.
    t.add(0, 9.f, 0.5f, kEntry);
    t.add(0, 10.f, 0.5f, kExit);
    comp.composite(t.px[0], t.lists, INFINITY, 0, 0);
    EXPECT_EQ(t.px[0].pending(), 0u);
    EXPECT_EQ(comp.segments(), cs.segments);
    EXPECT_EQ(comp.terminated_pixels(), 1u);
    EXPECT_NEAR(t.light[0].T, T, 1e-12);
  }
}

TEST(Compositor, NoEarlyTerminationWithZeroThreshold) {
  const double c[3] = {1, 1, 1};
  const TransferFunction tf = constant_tf(c, 0.999, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  Tile t(1);
  Compositor comp(ortho_view(), integ, 0.0, nullptr, t.px.data(), t.light.data());
  t.add(0, 0.f, 0.5f, kEntry);
  for (int i = 1; i < 6; ++i) t.add(0, float(i), 0.5f, kInterior);
  t.add(0, 6.f, 0.5f, kExit);
  comp.composite(t.px[0], t.lists, INFINITY, 0, 0);
  EXPECT_EQ(comp.segments(), 6u);
  EXPECT_EQ(t.px[0].done, 0);
  EXPECT_NEAR(t.light[0].T, std::pow(0.001, 6), 1e-25);
}

TEST(Compositor, FragmentsAtOrBeyondZLimitStayPending) {
  const double c1[3] = {0.9, 0.1, 0.3}, c2[3] = {0.05, 0.7, 1.0};
  const TransferFunction tf({{0, c1[0], c1[1], c1[2]}, {1, c2[0], c2[1], c2[2]}}, {{0, 0.2}, {1, 0.6}}, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  const float zf[7] = {0.5f, 1.f, 2.f, 3.f, 4.f, 5.f, 6.5f};
  const float ss[7] = {0.f, 0.25f, 0.5f, 1.f, 0.75f, 0.1f, 0.9f};
  for (bool batched : {false, true}) {
    std::unique_ptr<SegmentBatch> batch_a, batch_b;
    if (batched) {
      batch_a = std::make_unique<SegmentBatch>(integ, tf);
      batch_b = std::make_unique<SegmentBatch>(integ, tf);
    }
    Tile a(1), b(1);
    Compositor ca(ortho_view(), integ, 0.0, batch_a.get(), a.px.data(), a.light.data());
    Compositor cb(ortho_view(), integ, 0.0, batch_b.get(), b.px.data(), b.light.data());
    for (int i = 0; i < 7; ++i) {
      const uint32_t kind = i == 0 ? kEntry : i == 6 ? kExit : kInterior;
      a.add(0, zf[i], ss[i], kind);
      b.add(0, zf[i], ss[i], kind);
    }
    // a: in three steps; z_limit is exclusive (the fragment at 3 stays).
    ca.composite(a.px[0], a.lists, 0.5f, 0, 0);
    EXPECT_EQ(a.px[0].pending(), 7u);
    EXPECT_EQ(ca.segments(), 0u);
    ca.composite(a.px[0], a.lists, 3.f, 0, 0);
    EXPECT_EQ(a.px[0].pending(), 4u);
    EXPECT_EQ(a.px[0].z[0], 3.f);
    EXPECT_EQ(a.px[0].last_z, 2.f);
    EXPECT_EQ(a.px[0].last_s, 0.5f);
    EXPECT_EQ(a.px[0].inside, 1);
    EXPECT_EQ(ca.segments(), 2u);
    EXPECT_EQ(a.lists.live_fragments(), 4u);
    ca.composite(a.px[0], a.lists, 4.5f, 0, 0);
    EXPECT_EQ(a.px[0].pending(), 2u);
    EXPECT_EQ(ca.segments(), 4u);
    ca.composite(a.px[0], a.lists, INFINITY, 0, 0);
    EXPECT_EQ(a.px[0].pending(), 0u);
    EXPECT_EQ(ca.segments(), 6u);
    ca.flush();
    // b: all at once. Same light, bit for bit (same segments, same order).
    cb.composite(b.px[0], b.lists, INFINITY, 0, 0);
    cb.flush();
    EXPECT_EQ(cb.segments(), 6u);
    EXPECT_EQ(a.light[0].T, b.light[0].T);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.light[0].rgb[k], b.light[0].rgb[k]);
    EXPECT_LT(a.light[0].T, 1.0);
  }
}

// Many pixels with random fragments (overflowing the inline slots, more
// segments than a batch holds, several z_limit steps) through the batched
// path (every kernel width this CPU has) and the unbatched one: the same
// segments in the same order, the batched widths give the same bits, and
// batched and unbatched light agree within the batch kernel's documented
// bound against the scalar exact integrator (2e-9 per segment:
// test_segment_integrator.cpp, docs/accuracy.md: the Hermite rule's 1e-9
// per piece), summed over a pixel's segments. (1e-12 is not reachable:
// measured 3.5e-10 here, from the colour quadratures' tolerances.)
TEST(Compositor, BatchedAgreesWithUnbatched) {
  const TransferFunction tf({{0, 0.1, 0.2, 0.9}, {0.3, 0.9, 0.4, 0.1}, {0.55, 0.2, 1.0, 0.3}, {1, 1.0, 1.0, 1.0}},
                            {{0, 0.0}, {0.2, 0.05}, {0.5, 0.7}, {0.8, 0.3}, {1, 0.95}}, 1.5);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  std::vector<KernelWidth> widths{KernelWidth::Scalar};
  if (best_kernel_width() != KernelWidth::Scalar) widths.push_back(best_kernel_width());
  const size_t npix = 200;
  const int max_frags = 12;
  // The same random fragments for every run.
  struct F {
    size_t p;
    float z, s;
    uint32_t k;
  };
  std::vector<F> frags;
  {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u01(0.f, 1.f);
    std::uniform_int_distribution<int> nfrag(2, max_frags), kind(0, 2);
    for (size_t p = 0; p < npix; ++p) {
      const int n = nfrag(rng);
      for (int i = 0; i < n; ++i)
        frags.push_back({p, 10.f * u01(rng), 1.2f * u01(rng) - 0.1f, i == 0 ? uint32_t(kEntry) : uint32_t(kind(rng))});
    }
  }
  auto run = [&](SegmentBatch* batch, std::vector<PixelLight>* light, uint64_t* segments) {
    Tile t(npix);
    Compositor comp(ortho_view(), integ, 0.0, batch, t.px.data(), t.light.data());
    for (const F& f : frags) t.add(f.p, f.z, f.s, f.k);
    for (float z_limit : {2.5f, 5.f, 7.5f, INFINITY})
      for (size_t p = 0; p < npix; ++p) comp.composite(t.px[p], t.lists, z_limit, int(p % 8), int(p / 8 % 8));
    for (size_t p = 0; p < npix; ++p) EXPECT_EQ(t.px[p].pending(), 0u);
    EXPECT_EQ(t.lists.live_fragments(), 0u);
    comp.flush();
    *light = t.light;
    *segments = comp.segments();
  };
  std::vector<PixelLight> plain;
  uint64_t plain_segments = 0;
  run(nullptr, &plain, &plain_segments);
  EXPECT_GT(plain_segments, SegmentBatch::kCapacity);  // a batch fills at least once
  int opaque = 0;
  for (const PixelLight& l : plain) opaque += l.T < 0.9;
  EXPECT_GT(opaque, 20);  // the comparison is not between empty images
  std::vector<PixelLight> first;
  for (KernelWidth width : widths) {
    SegmentBatch batch(integ, tf, width);
    std::vector<PixelLight> light;
    uint64_t segments = 0;
    run(&batch, &light, &segments);
    EXPECT_EQ(segments, plain_segments);
    double worst = 0;
    for (size_t p = 0; p < npix; ++p) {
      worst = std::max(worst, std::abs(plain[p].T - light[p].T));
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(plain[p].rgb[k] - light[p].rgb[k]));
    }
    EXPECT_LE(worst, 2e-9 * (max_frags - 1)) << kernel_name(width, KernelPrecision::Double);
    if (first.empty()) {
      first = light;
    } else {
      for (size_t p = 0; p < npix; ++p) {  // every width: the same bits
        ASSERT_EQ(first[p].T, light[p].T) << p;
        for (int k = 0; k < 3; ++k) ASSERT_EQ(first[p].rgb[k], light[p].rgb[k]) << p;
      }
    }
  }
}

// Where a segment's colour and opacity are constant (scalar at or beyond
// the TF's ends, which are clamped), both paths are exact: they agree to
// 1e-12 with each other and with the closed form, over many pixels.
TEST(Compositor, BatchedAgreesWithUnbatchedToRoundingOnConstantSegments) {
  const double lo[3] = {0.9, 0.2, 0.1}, hi[3] = {0.1, 0.3, 0.8};
  const double a_lo = 0.25, a_hi = 0.6;
  const TransferFunction tf({{0, lo[0], lo[1], lo[2]}, {1, hi[0], hi[1], hi[2]}}, {{0, a_lo}, {1, a_hi}}, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  const size_t npix = 64;
  SegmentBatch batch(integ, tf);
  Tile a(npix), b(npix);
  Compositor plain(ortho_view(), integ, 0.0, nullptr, a.px.data(), a.light.data());
  Compositor batched(ortho_view(), integ, 0.0, &batch, b.px.data(), b.light.data());
  std::vector<double> wantT(npix, 1.0), want_r(npix, 0.0);
  for (size_t p = 0; p < npix; ++p) {
    // Cells alternating below 0 and above 1 in scalar, lengths k/8.
    float z = 0;
    for (int c = 0; c < 1 + int(p % 5); ++c) {
      const bool high = (p + size_t(c)) % 2;
      const float s = high ? 1.5f : -0.5f, L = float(1 + (p * 3 + size_t(c)) % 7) / 8.f;
      for (Tile* t : {&a, &b}) {
        t->add(p, z, s, kEntry);
        t->add(p, z + L, s, kExit);
      }
      const double T = std::pow(1 - (high ? a_hi : a_lo), L);
      want_r[p] += wantT[p] * (high ? hi[0] : lo[0]) * (1 - T);
      wantT[p] *= T;
      z += L;
    }
  }
  for (size_t p = 0; p < npix; ++p) {
    plain.composite(a.px[p], a.lists, INFINITY, 0, 0);
    batched.composite(b.px[p], b.lists, INFINITY, 0, 0);
  }
  batched.flush();
  for (size_t p = 0; p < npix; ++p) {
    EXPECT_NEAR(a.light[p].T, b.light[p].T, 1e-12) << p;
    EXPECT_NEAR(a.light[p].rgb[0], b.light[p].rgb[0], 1e-12) << p;
    EXPECT_NEAR(a.light[p].T, wantT[p], 1e-12) << p;
    EXPECT_NEAR(a.light[p].rgb[0], want_r[p], 1e-12) << p;
  }
}

TEST(Compositor, BatchedPathDefersLightToFlush) {
  const double c[3] = {0.5, 0.5, 0.5};
  const TransferFunction tf = constant_tf(c, 0.5, 1.0);
  const SegmentIntegrator integ(tf, Integrator::Exact);
  SegmentBatch batch(integ, tf);
  Tile t(1);
  Compositor comp(ortho_view(), integ, 0.0, &batch, t.px.data(), t.light.data());
  t.add(0, 0.f, 0.5f, kEntry);
  t.add(0, 1.f, 0.5f, kExit);
  comp.composite(t.px[0], t.lists, INFINITY, 0, 0);
  EXPECT_EQ(t.px[0].pending(), 0u);
  EXPECT_EQ(t.light[0].T, 1.0);  // queued, not yet applied
  comp.flush();
  EXPECT_NEAR(t.light[0].T, 0.5, 1e-14);
  EXPECT_NEAR(t.light[0].rgb[1], 0.25, 1e-14);
}

}  // namespace
}  // namespace zs
