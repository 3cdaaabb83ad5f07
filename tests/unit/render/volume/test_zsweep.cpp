// The ZSweep engine against closed forms and fine quadrature.
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "geometry/tets/topology.h"
#include "raster/image_sink.h"
#include "support/test_meshes.h"
#include "raster/tile_capture.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {
namespace {

using test::box_chord;
using test::box_mesh;
using test::spec_ray;
using test::settings;

Image render(const TetMesh& m, const RenderSettings& rs, RenderStats* st = nullptr) {
  const Topology t = build_topology(m);
  RenderStats local;
  return render_zsweep(m, t, rs, st ? st : &local);
}

// Constant density over a convex box: alpha = 1 - exp(-tau·L) per pixel,
// colour = c·alpha (premultiplied), L the chord of the pixel's ray.
void check_constant_box(Projection proj, uint32_t W, uint32_t H, bool single = false) {
  const glm::dvec3 lo{-1.0, -0.7, -0.5}, hi{1.0, 0.7, 0.5};
  const TetMesh m = box_mesh({6, 5, 4}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  const double a = 0.3, unit = 0.8;
  const double c[3] = {0.2, 0.5, 0.9};
  RenderSettings rs = settings(W, H, proj, TransferFunction({{0, c[0], c[1], c[2]}}, {{0, a}}, unit));
  rs.single_precision = single;
  RenderStats st;
  const Image img = render(m, rs, &st);
  const double tau = -std::log(1 - a) / unit;
  double worst = 0;
  size_t covered = 0;
  for (uint32_t j = 0; j < H; ++j)
    for (uint32_t i = 0; i < W; ++i) {
      glm::dvec3 o, d;
      spec_ray(rs.camera, W, H, int(i), int(j), &o, &d);
      const double L = box_chord(o, d, lo, hi);
      const double alpha = 1 - std::exp(-tau * L);
      const float* px = img.at(i, j);
      worst = std::max(worst, std::abs(px[3] - alpha));
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(px[k] - c[k] * alpha));
      covered += L > 0;
    }
  EXPECT_LE(worst, 2e-3);
  EXPECT_LE(worst, 1e-5) << "closed form should hold to float precision";
  EXPECT_GT(covered, W * H / 10);  // the box fills a good part of the image
  EXPECT_EQ(st.rendered_pixels, covered);
  EXPECT_EQ(st.pixel_hits, st.fragments);
}

TEST(ZSweep, ConstantDensityBoxOrthographicMatchesClosedForm) {
  check_constant_box(Projection::Orthographic, 96, 64);
}
TEST(ZSweep, ConstantDensityBoxPerspectiveMatchesClosedForm) {
  check_constant_box(Projection::Perspective, 64, 96);
}
TEST(ZSweep, ConstantDensityBoxSinglePrecisionMatchesClosedForm) {
  check_constant_box(Projection::Orthographic, 96, 64, true);
  check_constant_box(Projection::Perspective, 64, 96, true);
}

TEST(ZSweep, LinearScalarMatchesQuadratureWithExactIntegrator) {
  const glm::dvec3 lo{-1.0, -0.8, -0.6}, hi{1.0, 0.8, 0.6};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.22 * p.x + 0.15 * p.y - 0.2 * p.z; };
  const TetMesh m = box_mesh({1, 1, 3}, lo, hi, field);
  TransferFunction tf({{0.0, 0.1, 0.1, 0.9}, {0.35, 0.1, 0.9, 0.3}, {0.55, 0.9, 0.9, 0.1}, {1.0, 0.9, 0.1, 0.1}},
                      {{0.0, 0.0}, {0.3, 0.05}, {0.45, 0.9}, {0.55, 0.1}, {0.7, 0.6}, {1.0, 0.2}}, 0.5);
  const uint32_t W = 80, H = 60;
  double err[3] = {0, 0, 0};
  int which = 0;
  for (Integrator kind : {Integrator::Exact, Integrator::Linear, Integrator::Preintegrated}) {
    RenderSettings rs = settings(W, H, Projection::Orthographic, tf);
    rs.integrator = kind;
    const Image img = render(m, rs);
    for (uint32_t j = 0; j < H; j += 3)
      for (uint32_t i = 0; i < W; i += 3) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, W, H, int(i), int(j), &o, &d);
        double ref[4];
        test::march_box_ray(tf, field, o, d, lo, hi, ref);
        for (int k = 0; k < 4; ++k) err[which] = std::max(err[which], std::abs(img.at(i, j)[k] - ref[k]));
      }
    ++which;
  }
  std::printf("max abs error vs quadrature: exact %.2e, linear %.2e, preintegrated %.2e\n", err[0], err[1], err[2]);
  EXPECT_LE(err[0], 1e-4);
  EXPECT_GT(err[1], 10 * err[0]) << "the linear integrator ignores TF breakpoints inside a cell";
  EXPECT_GT(err[2], 10 * err[0]);
}

// The single-precision kernel on the same scene: within its bound
// (docs/accuracy.md: ~1e-6 per segment, a few segments per pixel) of the
// double kernel's image, which is not the same image bit for bit.
TEST(ZSweep, SinglePrecisionStaysWithinItsBoundOfDouble) {
  const glm::dvec3 lo{-1.0, -0.8, -0.6}, hi{1.0, 0.8, 0.6};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.22 * p.x + 0.15 * p.y - 0.2 * p.z; };
  const TetMesh m = box_mesh({3, 3, 3}, lo, hi, field);
  TransferFunction tf({{0.0, 0.1, 0.1, 0.9}, {0.35, 0.1, 0.9, 0.3}, {0.55, 0.9, 0.9, 0.1}, {1.0, 0.9, 0.1, 0.1}},
                      {{0.0, 0.0}, {0.3, 0.05}, {0.45, 0.9}, {0.55, 0.1}, {0.7, 0.6}, {1.0, 0.2}}, 0.5);
  RenderSettings rs = settings(96, 72, Projection::Orthographic, tf);
  RenderStats sd, ss;
  const Image dbl = render(m, rs, &sd);
  rs.single_precision = true;
  const Image sgl = render(m, rs, &ss);
  double worst = 0;
  for (uint32_t j = 0; j < 72; ++j)
    for (uint32_t i = 0; i < 96; ++i)
      for (int k = 0; k < 4; ++k) worst = std::max(worst, double(std::abs(dbl.at(i, j)[k] - sgl.at(i, j)[k])));
  std::printf("single against double: max difference %.2e over %llu segments\n", worst,
              (unsigned long long)ss.segments);
  EXPECT_EQ(sd.segments, ss.segments);  // the same sweep; only the light differs
  EXPECT_GT(worst, 0.0) << "the single-precision kernel did not run";
  EXPECT_LE(worst, 1e-5);
}

// Two boxes one behind the other (gap between), and a box with a cavity:
// light only along the mesh, never across a gap.
TEST(ZSweep, NonConvexGapsStayDark) {
  const double a = 0.4, unit = 1.0, tau = -std::log(1 - a) / unit;
  auto one = [](const glm::dvec3&) { return 1.0; };
  const glm::dvec3 alo{-1, -1, -2}, ahi{1, 1, -1}, blo{-1, -1, 1}, bhi{1, 1, 2};
  TetMesh two = box_mesh({3, 3, 2}, alo, ahi, one);
  test::append_mesh(two, box_mesh({3, 3, 2}, blo, bhi, one));
  // A 3x3x3 block with its centre cell removed: a closed cavity.
  const glm::dvec3 clo{-1.5, -1.5, -1.5}, chi{1.5, 1.5, 1.5}, ilo{-0.5, -0.5, -0.5}, ihi{0.5, 0.5, 0.5};
  const TetMesh cavity = box_mesh({3, 3, 3}, clo, chi, one, [](int i, int j, int k) { return !(i == 1 && j == 1 && k == 1); });

  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    const uint32_t W = 72, H = 56;
    RenderSettings rs = settings(W, H, proj, TransferFunction({{0, 1, 1, 1}}, {{0, a}}, unit));
    rs.camera.eye = {1.3, 0.9, 7.0};
    rs.camera.target = {0, 0, 0};
    rs.camera.height = 4.5;
    const Image img_two = render(two, rs);
    const Image img_cav = render(cavity, rs);
    double worst_two = 0, worst_cav = 0;
    for (uint32_t j = 0; j < H; ++j)
      for (uint32_t i = 0; i < W; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, W, H, int(i), int(j), &o, &d);
        const double L2 = box_chord(o, d, alo, ahi) + box_chord(o, d, blo, bhi);
        const double Lc = box_chord(o, d, clo, chi) - box_chord(o, d, ilo, ihi);
        worst_two = std::max(worst_two, std::abs(img_two.at(i, j)[3] - (1 - std::exp(-tau * L2))));
        worst_cav = std::max(worst_cav, std::abs(img_cav.at(i, j)[3] - (1 - std::exp(-tau * Lc))));
      }
    EXPECT_LE(worst_two, 1e-5) << int(proj);
    EXPECT_LE(worst_cav, 1e-5) << int(proj);
  }
}

TEST(ZSweep, InvisibleTetsAreCulledExactly) {
  // Scalar 0 (zero opacity) on one half, visible on the other: culling the
  // invisible half changes nothing in the image, only the counts.
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  auto step = [](const glm::dvec3& p) { return p.x < 0.01 ? 0.0 : 1.0; };
  const TetMesh m = box_mesh({4, 4, 4}, lo, hi, step);
  TransferFunction tf({{0, 1, 0.5, 0.2}}, {{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.5}}, 1.0);
  RenderStats st;
  const Image img = render(m, settings(48, 48, Projection::Orthographic, tf), &st);
  EXPECT_GT(st.tets_invisible, 0u);
  EXPECT_GT(st.faces_culled, 0u);
  // Reference: the same scene with the invisible tets removed from the mesh.
  TetMesh vis = m;
  vis.tets.clear();
  for (const Tet& t : m.tets) {
    double hi_s = 0;
    for (uint32_t v : t) hi_s = std::max(hi_s, m.scalars[v]);
    if (hi_s > 0.5) vis.tets.push_back(t);
  }
  const Image ref = render(vis, settings(48, 48, Projection::Orthographic, tf));
  for (size_t k = 0; k < img.rgba.size(); ++k) ASSERT_EQ(img.rgba[k], ref.rgba[k]) << k;
}

TEST(ZSweep, MaxListLengthAndBudgetDoNotChangeTheImage) {
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.3 * p.x * p.y + 0.2 * p.z; };
  // Long cells: each swept vertex projects faces reaching far behind the
  // sweep plane, so pixels hold more pending fragments than their records'
  // inline slots and the overflow pool (the budgeted part) is used.
  const TetMesh m = box_mesh({1, 1, 3}, lo, hi, field);
  TransferFunction tf({{0, 0.9, 0.3, 0.1}, {1, 0.1, 0.4, 0.9}}, {{0.0, 0.1}, {1.0, 0.7}}, 0.7);
  RenderSettings rs = settings(64, 64, Projection::Perspective, tf);
  RenderStats s0, s1, s2;
  const Image a = render(m, rs, &s0);
  ASSERT_GT(s0.peak_overflow_fragments, 0u) << "the scene must overflow the inline slots";
  EXPECT_GT(s0.peak_fragments, s0.peak_overflow_fragments);
  rs.max_list_length = 2;
  const Image b = render(m, rs, &s1);
  rs.max_list_length = 0;
  // The smallest budget that still renders (the pending fragments that are
  // not yet final must fit): below the unbounded peak, so the pool fills and
  // final fragments are composited early to make room.
  uint64_t blo = 1 << 16, bhi = 1 << 24;  // blo fails, bhi is ample
  Image c;
  while (bhi - blo > 16) {
    const uint64_t mid = (blo + bhi) / 2;
    rs.memory_budget_bytes = mid;
    try {
      RenderStats st;
      Image img = render(m, rs, &st);
      bhi = mid;
      c = std::move(img);
      s2 = st;
    } catch (const std::runtime_error&) {
      blo = mid;
    }
  }
  ASSERT_FALSE(c.rgba.empty());
  EXPECT_GT(s1.forced_composites, 0u);
  EXPECT_GT(s2.budget_flushes, 0u);
  EXPECT_LE(s2.peak_overflow_fragments, s2.fragment_capacity);
  EXPECT_LT(s2.fragment_capacity, s0.peak_overflow_fragments);
  for (size_t k = 0; k < a.rgba.size(); ++k) {
    ASSERT_EQ(a.rgba[k], b.rgba[k]) << k;
    ASSERT_EQ(a.rgba[k], c.rgba[k]) << k;
  }
  rs.memory_budget_bytes = 1000;
  EXPECT_THROW(render(m, rs), std::runtime_error);
}

TEST(ZSweep, EarlyTerminationStaysWithinItsBound) {
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.4 * p.z; };
  const TetMesh m = box_mesh({1, 1, 3}, lo, hi, field);
  TransferFunction tf({{0, 1, 1, 0.2}, {1, 0.2, 0.3, 1}}, {{0.0, 0.6}, {1.0, 0.95}}, 0.3);
  RenderSettings rs = settings(48, 40, Projection::Orthographic, tf);
  const Image full = render(m, rs);
  for (double t : {1.0, 4.0, 16.0}) {
    rs.early_termination = t;
    RenderStats st;
    const Image et = render(m, rs, &st);
    EXPECT_GT(st.early_terminated_pixels, 0u) << t;
    double worst = 0;
    for (size_t k = 0; k < full.rgba.size(); ++k) worst = std::max(worst, double(std::abs(full.rgba[k] - et.rgba[k])));
    EXPECT_LE(worst * 255.0, t / 2 + 1e-3) << t;
  }
}

}  // namespace
}  // namespace zs

namespace zs {
namespace {

TEST(ZSweep, ThreadsGiveBitIdenticalImages) {
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.3 * p.x * p.y + 0.2 * p.z; };
  const TetMesh m = test::box_mesh({5, 6, 4}, lo, hi, field);
  TransferFunction tf({{0, 0.9, 0.3, 0.1}, {1, 0.1, 0.4, 0.9}}, {{0.0, 0.1}, {0.4, 0.8}, {1.0, 0.3}}, 0.7);
  RenderSettings rs;
  rs.width = 70;
  rs.height = 45;
  rs.camera.projection = Projection::Perspective;
  rs.camera.eye = {2, 2.5, 3};
  rs.tf = tf;
  const Topology t = build_topology(m);
  RenderStats s1, s3;
  const Image one = render_zsweep(m, t, rs, &s1);
  rs.threads = 3;
  const Image three = render_zsweep(m, t, rs, &s3);
  EXPECT_EQ(s1.pixel_hits, s3.pixel_hits);
  EXPECT_EQ(s1.rendered_pixels, s3.rendered_pixels);
  ASSERT_EQ(one.rgba.size(), three.rgba.size());
  for (size_t k = 0; k < one.rgba.size(); ++k) ASSERT_EQ(one.rgba[k], three.rgba[k]) << k;
}

// Frames of one mesh reuse the per-view arrays (view_buffers.h): every frame
// is bit-identical to a fresh render of its view, across sizes, tile sizes,
// an eye inside the mesh (near-plane pieces) and a view that culls all.
TEST(ZSweep, ReusedViewBuffersGiveFreshImages) {
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.3 * p.x * p.y + 0.2 * p.z; };
  const TetMesh m = test::box_mesh({5, 4, 6}, lo, hi, field);
  const Topology t = build_topology(m);
  TransferFunction tf({{0, 0.9, 0.3, 0.1}, {1, 0.1, 0.4, 0.9}}, {{0.0, 0.1}, {0.4, 0.8}, {1.0, 0.3}}, 0.7);
  ViewBuffers buffers;
  struct View {
    uint32_t w, h, tile;
    glm::dvec3 eye;
    bool invisible;
  };
  for (const View& v : {View{90, 70, 16, {2, 2.5, 3}, false}, View{40, 30, 64, {-3, 1, 0.5}, false},
                        View{64, 48, 8, {0.2, 0.1, 0.3}, false}, View{50, 50, 16, {2, 2.5, 3}, true},
                        View{120, 20, 32, {0.5, -3, 1}, false}}) {
    RenderSettings rs;
    rs.width = v.w;
    rs.height = v.h;
    rs.tile_size = v.tile;
    rs.camera.projection = Projection::Perspective;
    rs.camera.eye = v.eye;
    rs.camera.fov_y = 70;
    rs.tf = v.invisible ? TransferFunction({{0, 1, 1, 1}}, {{0, 0.0}}, 1.0) : tf;
    RenderStats fresh_st;
    const Image fresh = render_zsweep(m, t, rs, &fresh_st);
    Image reused;
    {
      ZSweepRenderer r(m, t, rs, 0, &buffers);
      ImageSink sink(r.grid());
      r.render_tiles(sink, nullptr);
      reused = std::move(sink.image);
      EXPECT_EQ(r.stats().fragments, fresh_st.fragments);
    }
    EXPECT_EQ(v.invisible, fresh_st.fragments == 0);
    EXPECT_FALSE(buffers.items.empty() && !v.invisible) << "the renderer gives its arrays back";
    ASSERT_EQ(fresh.rgba.size(), reused.rgba.size());
    for (size_t k = 0; k < fresh.rgba.size(); ++k) ASSERT_EQ(fresh.rgba[k], reused.rgba[k]) << v.w << " at " << k;
  }
}

// Tiles sweep their own bins in the global sweep order: every pixel sees the
// same fragments in the same order, so the image does not depend on the tile
// size (one tile, tiles smaller than a face, odd sizes), for every scan
// strategy, on a mesh with faces crossing many tiles and a near-plane cut.
TEST(ZSweep, TileSizeGivesBitIdenticalImages) {
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.3 * p.x * p.y + 0.2 * p.z; };
  const TetMesh m = test::box_mesh({4, 3, 5}, lo, hi, field);
  const Topology t = build_topology(m);
  TransferFunction tf({{0, 0.9, 0.3, 0.1}, {1, 0.1, 0.4, 0.9}}, {{0.0, 0.1}, {0.4, 0.8}, {1.0, 0.3}}, 0.7);
  for (bool inside : {false, true}) {
    RenderSettings rs;
    rs.width = 83;
    rs.height = 61;
    rs.camera.projection = Projection::Perspective;
    rs.camera.eye = inside ? glm::dvec3{0.2, 0.1, 0.3} : glm::dvec3{2, 2.5, 3};
    rs.camera.fov_y = 70;
    rs.tf = tf;
    for (ScanStrategy scan : {ScanStrategy::BBox, ScanStrategy::Span, ScanStrategy::BConvert}) {
      rs.scan = scan;
      rs.tile_size = 1000;
      RenderStats s0;
      const Image whole = render_zsweep(m, t, rs, &s0);
      EXPECT_EQ(s0.tiles, 1u);
      EXPECT_GT(s0.rendered_pixels, 500u);
      for (uint32_t tile : {1u, 7u, 16u, 64u}) {
        rs.tile_size = tile;
        rs.threads = tile == 7 ? 2 : 1;
        RenderStats st;
        const Image img = render_zsweep(m, t, rs, &st);
        EXPECT_EQ(st.tiles, uint64_t((83 + tile - 1) / tile) * ((61 + tile - 1) / tile));
        EXPECT_EQ(st.fragments, s0.fragments) << tile;
        EXPECT_EQ(st.segments, s0.segments) << tile;
        for (size_t k = 0; k < whole.rgba.size(); ++k)
          ASSERT_EQ(whole.rgba[k], img.rgba[k]) << "tile " << tile << " scan " << to_string(scan) << " at " << k;
      }
    }
  }
}

}  // namespace
}  // namespace zs

namespace zs {
namespace {

// The eye inside the mesh (perspective) and the eye plane through it
// (orthographic): only the part of each ray at positive distance counts.
TEST(ZSweep, EyeInsideMeshIntegratesFromTheEye) {
  const glm::dvec3 lo{-1.0, -0.8, -1.2}, hi{1.1, 0.9, 1.0};
  const TetMesh m = test::box_mesh({5, 4, 6}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  const double a = 0.35, unit = 1.0, tau = -std::log(1 - a) / unit;
  for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
    RenderSettings rs;
    rs.width = 64;
    rs.height = 48;
    rs.camera.projection = proj;
    rs.camera.eye = {0.13, -0.07, 0.21};
    rs.camera.target = {0.5, 0.2, -1.0};
    rs.camera.up = {0, 1, 0};
    rs.camera.fov_y = 70;
    rs.camera.height = 1.3;
    rs.tf = TransferFunction({{0, 1, 1, 1}}, {{0, a}}, unit);
    RenderStats st;
    const Image img = render_zsweep(m, build_topology(m), rs, &st);
    EXPECT_GT(st.faces_clipped, 0u);
    double worst = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        const double L = box_chord(o, d, lo, hi);  // from t = 0: the eye is inside
        worst = std::max(worst, std::abs(img.at(i, j)[3] - (1 - std::exp(-tau * L))));
      }
    EXPECT_LE(worst, 1e-5) << int(proj);
  }
}

// Cell data: each tet keeps its own value, and a ray through two regions of
// different values is two constant segments (test::TwoRegions' closed form),
// from outside the mesh and from an eye inside it, in both projections.
TEST(ZSweep, CellDataInTwoRegionsMatchClosedForm) {
  const test::TwoRegions two;
  const TetMesh m = two.mesh();
  const Topology topo = build_topology(m);
  for (bool inside : {false, true})
    for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
      RenderSettings rs = settings(80, 60, proj, two.tf());
      if (inside) rs.camera.eye = {-0.43, 0.11, 0.17}, rs.camera.target = {1.0, -0.2, -0.35}, rs.camera.fov_y = 70;
      RenderStats st;
      const Image img = render_zsweep(m, topo, rs, &st);
      EXPECT_EQ(st.cell_data_tets, m.num_tets());
      if (inside) EXPECT_GT(st.faces_clipped, 0u);
      const double worst = two.worst(img, rs);
      size_t both = 0;  // rays through both regions
      for (uint32_t j = 0; j < rs.height; ++j)
        for (uint32_t i = 0; i < rs.width; ++i) {
          glm::dvec3 o, d;
          spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
          double t0, t1;
          glm::dvec3 hi0 = two.hi, lo1 = two.lo;
          hi0.x = lo1.x = two.x_mid();
          both += test::box_span(o, d, two.lo, hi0, &t0, &t1) && test::box_span(o, d, lo1, two.hi, &t0, &t1);
        }
      EXPECT_LE(worst, 1e-5) << "inside " << inside << " projection " << int(proj);
      EXPECT_GT(both, rs.width * rs.height / 40) << "inside " << inside << " projection " << int(proj);
    }
}

// The same tets with point data averaged from the cells are a different
// image (the cell test above would pass for no reason if the values were
// never read), and with one value everywhere cell and point data agree
// bit for bit.
TEST(ZSweep, CellDataWithOneValueIsThePointImage) {
  const test::TwoRegions two;
  TetMesh cell = two.mesh();
  for (double& v : cell.cell_scalars) v = two.value[1];
  TetMesh point = cell;
  point.cell_scalars.clear();
  point.scalars.assign(point.num_points(), two.value[1]);
  const RenderSettings rs = settings(48, 40, Projection::Perspective, two.tf());
  const Image a = render(cell, rs), b = render(point, rs);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(0, std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)));
  TetMesh averaged = two.mesh();
  average_cell_scalars_onto_points(averaged);
  const Image c = render(two.mesh(), rs), d = render(averaged, rs);
  double diff = 0;
  for (size_t k = 0; k < c.rgba.size(); ++k) diff = std::max(diff, double(std::abs(c.rgba[k] - d.rgba[k])));
  EXPECT_GT(diff, 0.05);
}

// Clip planes cut every segment exactly: a constant-density box cut by an
// oblique plane and a crop box is still convex, each ray's light the closed
// form of its chord through what is kept; in both projections and from an
// eye inside the kept part. Tets wholly outside are not projected.
TEST(ZSweep, ClipPlanesMatchClosedForm) {
  const glm::dvec3 lo{-1.0, -0.7, -0.5}, hi{1.0, 0.7, 0.5};
  const TetMesh m = box_mesh({6, 5, 4}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  const Topology topo = build_topology(m);
  const double a = 0.4, unit = 0.6, tau = -std::log(1 - a) / unit;
  const double c[3] = {0.3, 0.6, 0.8};
  ClipRegion clip;
  clip.planes.push_back({glm::normalize(glm::dvec3(0.6, 0.3, -0.5)), -0.13});
  clip.add_box({-0.83, -1, -0.41}, {1, 0.52, 1});
  for (bool inside : {false, true})
    for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
      RenderSettings rs = settings(72, 56, proj, TransferFunction({{0, c[0], c[1], c[2]}}, {{0, a}}, unit));
      if (inside) rs.camera.eye = {-0.5, 0.1, 0.2}, rs.camera.target = {1.0, -0.2, -0.35}, rs.camera.fov_y = 80;
      rs.clip = clip;
      RenderStats st;
      const Image img = render_zsweep(m, topo, rs, &st);
      double worst = 0;
      size_t cut = 0;  // rays the planes shorten
      for (uint32_t j = 0; j < rs.height; ++j)
        for (uint32_t i = 0; i < rs.width; ++i) {
          glm::dvec3 o, d;
          spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
          const double L = box_chord(o, d, lo, hi, clip), alpha = 1 - std::exp(-tau * L);
          const float* px = img.at(i, j);
          worst = std::max(worst, double(std::abs(px[3] - alpha)));
          for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(px[k] - c[k] * alpha));
          cut += L > 0 && L < box_chord(o, d, lo, hi) - 1e-6;
        }
      const std::string what = std::string(inside ? "inside, " : "") + (proj == Projection::Perspective ? "perspective" : "orthographic");
      EXPECT_LE(worst, 2e-5) << what;
      EXPECT_GT(cut, rs.width * rs.height / 20) << what;
      EXPECT_GT(st.tets_clipped, 0u) << what;
      EXPECT_GT(st.segments_clipped, 0u) << what;
    }
}

// Cell data and clip planes together: the two-region closed form, cut.
TEST(ZSweep, ClipPlanesCutCellData) {
  const test::TwoRegions two;
  const TetMesh m = two.mesh();
  ClipRegion clip;
  clip.planes.push_back({glm::dvec3(-0.2, 1.0, 0.7), -0.1});
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    RenderSettings rs = settings(64, 48, proj, two.tf());
    rs.clip = clip;
    const Image img = render(m, rs);
    const double worst = two.worst(img, rs);
    EXPECT_LE(worst, 2e-5) << int(proj);
  }
}

// Planes that keep the whole mesh change nothing, bit for bit (each segment
// is wholly kept); a plane that keeps none of it leaves the background.
TEST(ZSweep, ClipPlanesKeepingEverythingOrNothing) {
  const TetMesh m = box_mesh({5, 4, 3}, {-1, -0.7, -0.5}, {1, 0.7, 0.5},
                             [](const glm::dvec3& p) { return p.x * p.x + 0.5 * p.y; });
  const RenderSettings plain = settings(48, 40, Projection::Perspective,
                                        TransferFunction({{0, 1, 0.5, 0}, {1.5, 0, 0.5, 1}}, {{0, 0.1}, {1.5, 0.7}}, 1));
  RenderSettings all = plain, none = plain;
  all.clip.planes.push_back({glm::dvec3(0.3, 0.2, 1.0), -4.0});
  all.clip.add_box({-3, -3, -3}, {3, 3, 3});
  none.clip.planes.push_back({glm::dvec3(1.0, 0.0, 0.0), 1.5});  // keeps x <= -1.5
  RenderStats s_all, s_none;
  const Image a = render(m, plain), b = render(m, all, &s_all), c = render(m, none, &s_none);
  EXPECT_EQ(0, std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)));
  EXPECT_EQ(s_all.segments_clipped, 0u);
  EXPECT_EQ(s_none.tets_clipped, m.num_tets());
  for (float v : c.rgba) ASSERT_EQ(v, 0.0f);
}

// An opaque sphere inside a constant-density box (a mixed scene's opaque
// layer, drawn here by hand: flat colour, exact hit depth): each ray's light
// is the volume's emission up to the hit, then the sphere's colour times the
// transmittance to it; rays that miss see the box's whole chord over the
// background. Both projections, the eye outside and inside the box, with a
// clip plane too.
TEST(ZSweep, OpaqueSphereInsideAVolumeMatchesClosedForm) {
  const glm::dvec3 lo{-1.0, -0.7, -0.5}, hi{1.0, 0.7, 0.5};
  const TetMesh m = box_mesh({6, 5, 4}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  const Topology topo = build_topology(m);
  const double a = 0.35, unit = 0.7, tau = -std::log(1 - a) / unit;
  const double c[3] = {0.2, 0.5, 0.9}, sc[3] = {0.9, 0.6, 0.1}, bg[4] = {0.05, 0.1, 0.15, 1.0};
  const glm::dvec3 centre{0.15, -0.05, 0.02};
  const double radius = 0.33;
  auto sphere_hit = [&](glm::dvec3 o, glm::dvec3 d) {  // nearest t > 0, or inf
    const glm::dvec3 oc = o - centre;
    const double b = glm::dot(oc, d), q = glm::dot(oc, oc) - radius * radius, disc = b * b - q;
    if (disc < 0) return double(INFINITY);
    const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
    return t0 > 0 ? t0 : t1 > 0 ? t1 : double(INFINITY);
  };
  for (int variant = 0; variant < 3; ++variant)
    for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
      RenderSettings rs = settings(72, 56, proj, TransferFunction({{0, c[0], c[1], c[2]}}, {{0, a}}, unit));
      for (int k = 0; k < 4; ++k) rs.background[k] = bg[k];
      if (variant == 1) rs.camera.eye = {-0.8, 0.4, 0.35}, rs.camera.target = centre, rs.camera.fov_y = 75;
      if (variant == 2) rs.clip.planes.push_back({glm::dvec3(0.2, 1.0, 0.3), -0.02});
      // The layer: per tile, RGBA over the background and the hit's view depth.
      TileGrid grid{rs.width, rs.height, 32, 5};
      rs.tile_size = 32;
      TileCapture layer(grid);
      const View view(rs.camera, rs.width, rs.height);
      for (uint32_t t = 0; t < grid.count(); ++t) {
        const TileRect r = grid.rect(t);
        std::vector<float> px;
        for (uint32_t y = r.y0; y < r.y1; ++y)
          for (uint32_t x = r.x0; x < r.x1; ++x) {
            glm::dvec3 o, d;
            spec_ray(rs.camera, rs.width, rs.height, int(x), int(y), &o, &d);
            const double th = sphere_hit(o, d);
            const bool hit = std::isfinite(th);
            for (int k = 0; k < 3; ++k) px.push_back(float(hit ? sc[k] : bg[k]));
            px.push_back(float(hit ? 1.0 : bg[3]));
            px.push_back(hit ? float(view.depth(o + th * d)) : INFINITY);
          }
        layer.tile(r, px.data());
      }
      const CapturedOpaqueLayer under(layer);
      ZSweepRenderer zr(m, topo, rs, 0);
      zr.set_opaque_layer(&under);
      ImageSink sink(zr.grid());
      RenderStats st;
      zr.render_tiles(sink, nullptr, &st);
      double worst = 0;
      for (uint32_t j = 0; j < rs.height; ++j)
        for (uint32_t i = 0; i < rs.width; ++i) {
          glm::dvec3 o, d;
          spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
          const double th = sphere_hit(o, d);
          ClipRegion keep = rs.clip;
          if (std::isfinite(th)) keep.planes.push_back({d, -glm::dot(d, o + th * d)});  // t <= th
          const double T = std::exp(-tau * box_chord(o, d, lo, hi, keep));
          const double* under_rgb = std::isfinite(th) ? sc : bg;
          const double under_a = std::isfinite(th) ? 1.0 : bg[3];
          const float* px = sink.image.at(i, j);
          for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(px[k] - (c[k] * (1 - T) + T * under_rgb[k])));
          worst = std::max(worst, std::abs(px[3] - ((1 - T) + T * under_a)));
        }
      EXPECT_LE(worst, 2e-5) << "variant " << variant << " projection " << int(proj);
      EXPECT_GT(st.rays_stopped, 40u) << "variant " << variant << " projection " << int(proj);
    }
}

}  // namespace
}  // namespace zs
