// Translucent sphere modes (render/spheres/translucent_tile.h) against closed-form
// composites of shells, each other and the Embree reference; the digest's
// error bound (Eq. 4.2) and its worked example; weighted sum's failure;
// tiles, threads and culling never change a bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>

#include "raster/image_sink.h"
#include "render/reference/sphere_reference.h"
#include "render/spheres/fragment_composite.h"
#include "render/spheres/sphere_renderer.h"
#include "render/spheres/translucent_tile.h"

namespace zs {
namespace {

struct Out {
  Image rgba;
  std::vector<float> z;
  SphereStats stats;
};

Out render(const SphereSet& s, const std::vector<glm::vec4>& colors, const SphereRenderSettings& rs) {
  const SphereGrid g = build_sphere_grid(s, rs.grid);
  SphereRenderer r(s, colors, g, rs);
  ImageSink sink(r.grid());
  r.render_tiles(sink, nullptr);
  return {std::move(sink.image), std::move(sink.z), r.stats()};
}

SphereRenderSettings settings(Projection p, SphereMode m, uint32_t w = 48, uint32_t h = 40) {
  SphereRenderSettings rs;
  rs.width = w, rs.height = h;
  rs.camera.projection = p;
  rs.camera.eye = {0.1, 0.05, 10};
  rs.camera.target = {0, 0, 0};
  rs.camera.height = 6;
  rs.camera.fov_y = 40;
  rs.tile_size = 16;
  rs.mode = m;
  rs.tolerance = 0;
  rs.max_layers = 0;
  rs.shading.model = ShadingModel::Flat;
  return rs;
}

bool same_bits(const Out& a, const Out& b) {
  return a.rgba.rgba == b.rgba.rgba && std::memcmp(a.z.data(), b.z.data(), a.z.size() * 4) == 0;
}

double max_diff(const Out& a, const Out& b) {
  double m = 0;
  for (size_t k = 0; k < a.rgba.rgba.size(); ++k) m = std::max(m, double(std::abs(a.rgba.rgba[k] - b.rgba.rgba[k])));
  return m;
}

TEST(FragmentComposite, EqualAlphaStackReachesOneMinusPowerAndTheBoundOf32Layers) {
  // f(n) = 1 − (1 − α)^n (spheres digest §2.3.7), and the α that 32 layers need for t = 8.
  for (double a : {0.05, 0.121767, 0.5}) {
    double acc[4] = {0, 0, 0, 0};
    const double c[4] = {a, a, a, a};
    for (int n = 1; n <= 40; ++n) {
      composite_under(acc, c);
      EXPECT_NEAR(acc[3], 1 - std::pow(1 - a, n), 1e-14);
    }
  }
  const double amin = 1 - std::pow(4.0 / 255.0, 1.0 / 32.0);
  EXPECT_NEAR(amin, 0.121767, 1e-6);
  EXPECT_LE(std::pow(1 - amin, 32), stop_threshold(8) + 1e-15);
  EXPECT_LT(stop_threshold(0), 0);  // t = 0 never stops, even at alpha 1
  const double almost[4] = {0, 0, 0, 1 - 1e-12};
  EXPECT_FALSE(saturated(almost, stop_threshold(0)));
  EXPECT_TRUE(saturated(almost, stop_threshold(1)));
  EXPECT_TRUE(FragKey({1.0, frag_code(3, false)}) < FragKey({1.0, frag_code(3, true)}));
  EXPECT_TRUE(FragKey({1.0, frag_code(2, true)}) < FragKey({1.0, frag_code(3, false)}));
}

// Concentric shells seen through their centre region, flat colours: each ray
// crosses outer, inner, inner, outer (or outer, outer), a closed-form composite.
TEST(SphereTranslucency, SortedEqualsClosedFormShellsBothProjections) {
  SphereSet s;
  s.centres = {{0, 0, 0}, {0, 0, 0}};
  s.radii = {2.5, 1.2};
  const std::vector<glm::vec4> col = {{1.0f, 0.2f, 0.1f, 0.4f}, {0.1f, 0.9f, 0.3f, 0.25f}};
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings rs = settings(p, SphereMode::Sorted);
    rs.background[0] = 0.2, rs.background[3] = 1;
    const Out o = render(s, col, rs);
    const View v(rs.camera, rs.width, rs.height);
    int inner = 0, outer = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 orig, u;
        v.ray(i, j, &orig, &u);
        auto hits = [&](double r) {  // ray through the common centre's sphere, distance test
          const double b = glm::dot(-orig, u), d2 = glm::dot(orig, orig) - b * b;
          return d2 < r * r - 1e-6 ? 1 : d2 > r * r + 1e-6 ? 0 : -1;
        };
        const int ho = hits(2.5), hi = hits(1.2);
        if (ho < 0 || hi < 0) continue;  // grazing
        std::vector<int> seq;
        if (ho) seq = hi ? std::vector<int>{0, 1, 1, 0} : std::vector<int>{0, 0};
        double acc[4] = {0, 0, 0, 0};
        for (int k : seq) {
          const double c[4] = {col[k].r * col[k].a, col[k].g * col[k].a, col[k].b * col[k].a, col[k].a};
          composite_under(acc, c);
        }
        composite_under(acc, rs.background);
        const float* px = o.rgba.at(i, j);
        for (int q = 0; q < 4; ++q) EXPECT_NEAR(px[q], acc[q], 1e-6) << i << "," << j;
        inner += hi, outer += ho && !hi;
      }
    EXPECT_GT(inner, 50);
    EXPECT_GT(outer, 50);
  }
}

TEST(SphereTranslucency, EyeInsideAShellSeesOnlyItsExit) {
  SphereSet s;
  s.centres = {{0.1, 0.05, 9.0}};
  s.radii = {3.0};  // holds the eye (0.1, 0.05, 10)
  const std::vector<glm::vec4> col = {{0.6f, 0.5f, 0.4f, 0.3f}};
  for (bool front : {false, true}) {
    SphereRenderSettings rs = settings(Projection::Perspective, SphereMode::Sorted);
    rs.front_surfaces_only = front;
    const Out o = render(s, col, rs);
    for (size_t p = 0; p < o.z.size(); ++p) {
      ASSERT_TRUE(std::isfinite(o.z[p]));
      EXPECT_NEAR(o.rgba.rgba[p * 4 + 0], 0.6 * 0.3, 1e-6);
      EXPECT_NEAR(o.rgba.rgba[p * 4 + 3], 0.3, 1e-6);
    }
  }
}

// A random set of mixed opacities, some opaque, some clear, interpenetrating.
void mixed_set(size_t n, uint64_t seed, SphereSet* s, std::vector<glm::vec4>* col) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const float alphas[] = {1.f, 0.3f, 0.5f, 0.15f, 0.f, 0.8f, 0.05f};
  for (size_t k = 0; k < n; ++k) {
    s->centres.push_back({2.5 * u(rng), 2.0 * u(rng), 2.5 * u(rng)});
    s->radii.push_back(0.15 + 0.5 * (u(rng) + 1) / 2);
    col->push_back({float(u(rng) + 1) / 2, float(u(rng) + 1) / 2, float(u(rng) + 1) / 2, alphas[k % 7]});
  }
}

TEST(SphereTranslucency, PeelToCompletionIsSortedAndDualPeelAndReferenceAgree) {
  SphereSet s;
  std::vector<glm::vec4> col;
  mixed_set(300, 5, &s, &col);
  for (Projection p : {Projection::Orthographic, Projection::Perspective})
    for (bool front : {false, true}) {
      SphereRenderSettings rs = settings(p, SphereMode::Sorted, 64, 48);
      rs.shading.model = ShadingModel::Phong;
      rs.front_surfaces_only = front;
      rs.background[2] = 0.3, rs.background[3] = 1;
      const Out sorted = render(s, col, rs);
      rs.mode = SphereMode::Peel;
      const Out peel = render(s, col, rs);
      EXPECT_TRUE(same_bits(sorted, peel));
      EXPECT_EQ(sorted.stats.composited, peel.stats.composited);
      EXPECT_GT(peel.stats.layers_max, 3u);
      rs.mode = SphereMode::DualPeel;
      const Out dual = render(s, col, rs);
      EXPECT_LE(max_diff(sorted, dual), 1e-6);
      const View v(rs.camera, rs.width, rs.height);
      const SphereReferenceImage ref =
          render_sphere_reference_translucent(s, col, rs.shading, v, rs.background, 1, front);
      double m = 0;
      for (size_t k = 0; k < ref.rgba.rgba.size(); ++k)
        m = std::max(m, double(std::abs(ref.rgba.rgba[k] - sorted.rgba.rgba[k])));
      EXPECT_LE(m, 1e-5);
    }
}

// Alpha exactly 1 in double ends a pixel at t = 0 too: composite_under
// then adds c·0, so the image is the every-fragment composite bit for bit.
TEST(SphereTranslucency, AlphaOneInDoubleEndsThePixelLosslessly) {
  double acc[4] = {0.25, 0.5, 0.125, 1.0};
  const double before[4] = {acc[0], acc[1], acc[2], acc[3]};
  const double c[4] = {0.4, 0.3, 0.2, 0.5};
  ASSERT_TRUE(opaque_now(acc));
  composite_under(acc, c);
  EXPECT_EQ(std::memcmp(acc, before, sizeof acc), 0);
  SphereSet s;
  std::vector<glm::vec4> col;
  for (int k = 0; k < 60; ++k) {  // nested shells: 120 fragments of alpha 0.5 per centre ray
    s.centres.push_back({0, 0, 0});
    s.radii.push_back(1.0 + 0.03 * k);
    col.push_back({0.2f + 0.01f * float(k), 0.5f, 0.9f, 0.5f});
  }
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings rs = settings(p, SphereMode::Sorted);
    const Out sorted = render(s, col, rs);
    EXPECT_EQ(sorted.stats.pixels_stopped, 0u);  // no tolerance stop at t = 0
    EXPECT_LT(sorted.stats.composited, 120u * sorted.stats.rendered_pixels / 2);
    rs.mode = SphereMode::Peel;
    const Out peel = render(s, col, rs);
    EXPECT_TRUE(same_bits(sorted, peel));
    const View v(rs.camera, rs.width, rs.height);
    const SphereReferenceImage ref = render_sphere_reference_translucent(s, col, rs.shading, v, rs.background, 1, false);
    for (size_t k = 0; k < ref.rgba.rgba.size(); ++k) EXPECT_NEAR(ref.rgba.rgba[k], sorted.rgba.rgba[k], 1e-6) << k;
  }
}

TEST(SphereTranslucency, SortedOfOpaqueSpheresIsTheOpaqueImage) {
  SphereSet s;
  std::vector<glm::vec4> col;
  mixed_set(200, 9, &s, &col);
  for (glm::vec4& c : col) c.a = 1.f;
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings rs = settings(p, SphereMode::Sorted);
    rs.shading.model = ShadingModel::Phong;
    const Out sorted = render(s, col, rs);
    rs.mode = SphereMode::Opaque;
    EXPECT_TRUE(same_bits(sorted, render(s, col, rs)));
  }
}

TEST(SphereTranslucency, TilesThreadsAndCullingChangeNoBit) {
  SphereSet s;
  std::vector<glm::vec4> col;
  mixed_set(3000, 11, &s, &col);
  for (SphereMode m : {SphereMode::Sorted, SphereMode::Peel, SphereMode::DualPeel, SphereMode::Weighted}) {
    SphereRenderSettings rs = settings(Projection::Perspective, m, 80, 64);
    rs.tolerance = 8, rs.max_layers = 6;
    rs.shading.model = ShadingModel::Phong;
    const Out a = render(s, col, rs);
    SphereRenderSettings b = rs;
    b.threads = 2, b.tile_size = 8;
    EXPECT_TRUE(same_bits(a, render(s, col, b))) << to_string(m);
    b = rs;
    b.culling = false;
    EXPECT_TRUE(same_bits(a, render(s, col, b))) << to_string(m);
    // Opaque spheres did hide others (translucent ones hide nothing).
    EXPECT_GT(a.stats.vis.spheres_pyramid_culled + a.stats.vis.spheres_occluded_cells +
                  a.stats.vis.spheres_pixel_culled, 100u);
    EXPECT_LT(a.stats.vis.occluders, s.size() / 5);
    b = rs;
    b.grid = 3;
    EXPECT_TRUE(same_bits(a, render(s, col, b))) << to_string(m);
  }
}

// A head-on stack of n equal spheres, front surfaces, orthographic: each
// pixel of the centre sees n fragments of one alpha.
Out stack(int n, float alpha, SphereMode m, double tolerance, uint32_t cap, glm::vec3 rgb = {1, 1, 1},
          double bg_grey = 0) {
  SphereSet s;
  std::vector<glm::vec4> col;
  for (int k = 0; k < n; ++k) {
    s.centres.push_back({0, 0, -0.5 * k});
    s.radii.push_back(2.0);
    col.push_back({rgb.r, rgb.g, rgb.b, alpha});
  }
  SphereRenderSettings rs = settings(Projection::Orthographic, m, 16, 16);
  rs.camera.eye = {0, 0, 10};
  rs.front_surfaces_only = true;
  rs.tolerance = tolerance, rs.max_layers = cap;
  for (int q = 0; q < 3; ++q) rs.background[q] = bg_grey;
  rs.background[3] = 1;
  return render(s, col, rs);
}

TEST(SphereTranslucency, IncompleteImageBoundHoldsAboveTheAlphaOf32Layers) {
  // t = 8, n = 32: within t/2 levels when α >= 0.121767, even for 60 layers.
  for (float a : {0.125f, 0.2f, 0.5f}) {
    const Out exact = stack(60, a, SphereMode::Sorted, 0, 0);
    const Out peel = stack(60, a, SphereMode::Peel, 8, 32);
    const Out sorted = stack(60, a, SphereMode::Sorted, 8, 0);
    EXPECT_LE(max_diff(exact, peel), 8.0 / 510 + 1e-7) << a;
    EXPECT_LE(max_diff(exact, sorted), 8.0 / 510 + 1e-7) << a;
    EXPECT_LE(peel.stats.layers_max, 32u);
  }
  // Below it the cap cuts layers that matter: the error exceeds t/2 levels.
  const Out exact = stack(60, 0.05f, SphereMode::Sorted, 0, 0);
  const Out peel = stack(60, 0.05f, SphereMode::Peel, 8, 32);
  EXPECT_EQ(peel.stats.layers_max, 32u);
  EXPECT_GT(max_diff(exact, peel), 8.0 / 510);
}

TEST(SphereTranslucency, PixelOfTrueValue170WithTolerance4EndsIn168To172) {
  // Spheres of colour c and α 0.3 over black: exact red = c·(1 − 0.7^20) = 170/255.
  const float c = float((170.0 / 255.0) / (1 - std::pow(0.7, 20)));
  const Out exact = stack(20, 0.3f, SphereMode::Sorted, 0, 0, {c, c, c});
  const Out cut = stack(20, 0.3f, SphereMode::Peel, 4, 0, {c, c, c});
  const size_t centre = (8 * 16 + 8) * 4;
  EXPECT_NEAR(exact.rgba.rgba[centre] * 255.0, 170.0, 1e-3);
  const double v = cut.rgba.rgba[centre] * 255.0;
  EXPECT_GE(v, 168.0);
  EXPECT_LE(v, 172.0);
  EXPECT_GT(cut.stats.pixels_stopped, 0u);
  EXPECT_LT(cut.stats.layers_max, 20u);  // it did stop early
}

TEST(SphereTranslucency, WeightedSumSaturatesOnOverlappingLowAlphaSpheres) {
  // 20 layers of α 0.1, white over black: exact 1 − 0.9^20 ≈ 0.878;
  // the weighted sum adds 20 · 0.1 = 2 and clamps at 1.
  const Out exact = stack(20, 0.1f, SphereMode::Sorted, 0, 0);
  const Out w = stack(20, 0.1f, SphereMode::Weighted, 0, 0);
  const size_t centre = (8 * 16 + 8) * 4;
  EXPECT_NEAR(exact.rgba.rgba[centre], 1 - std::pow(0.9, 20), 1e-6);
  EXPECT_EQ(w.rgba.rgba[centre], 1.f);
  // One layer: exact.
  EXPECT_LE(max_diff(stack(1, 0.3f, SphereMode::Sorted, 0, 0), stack(1, 0.3f, SphereMode::Weighted, 0, 0)), 1e-6);
}

TEST(SphereTranslucency, DualPeelWithCapShowsNearestAndFarthestOnly) {
  const Out exact = stack(12, 0.3f, SphereMode::Sorted, 0, 0, {1, 0.5f, 0.2f}, 0.4);
  const Out dual = stack(12, 0.3f, SphereMode::DualPeel, 0, 4, {1, 0.5f, 0.2f}, 0.4);
  EXPECT_EQ(dual.stats.layers_max, 4u);  // two passes: 2 front + 2 back layers
  EXPECT_GT(max_diff(exact, dual), 0.01);
}

}  // namespace
}  // namespace zs

namespace zs {
namespace {

// More fragments per pixel than sorted's k-buffer holds: several passes,
// still the peeled (exact) sequence bit for bit, both surfaces, both projections.
TEST(SphereTranslucency, SortedBeyondItsBufferTakesMorePassesAndStaysExact) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  SphereSet s;
  std::vector<glm::vec4> col;
  for (int k = 0; k < 80; ++k) {  // nested, large: every centre ray crosses most of them twice
    s.centres.push_back({0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)});
    s.radii.push_back(1.0 + 2.0 * (u(rng) + 1) / 2);
    col.push_back({float(u(rng) + 1) / 2, 0.5f, float(u(rng) + 1) / 2, 0.04f});
  }
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings rs = settings(p, SphereMode::Sorted, 40, 32);
    rs.shading.model = ShadingModel::Phong;
    const Out sorted = render(s, col, rs);
    rs.mode = SphereMode::Peel;
    const Out peel = render(s, col, rs);
    EXPECT_TRUE(same_bits(sorted, peel));
    EXPECT_GT(peel.stats.layers_max, 2 * TranslucentTile::kSortedLayers);
    // The buffer grows after the first pass: deep pixels end in the second.
    EXPECT_GT(sorted.stats.passes, sorted.stats.tiles);
    EXPECT_LE(sorted.stats.passes, 2 * sorted.stats.tiles);
    // Where the budget leaves no room to grow, a pass per 8 layers or so
    // (a full buffer keeps its nearest half), still exact.
    rs.mode = SphereMode::Sorted;
    Out tight;
    for (rs.memory_budget_bytes = 1 << 16;; rs.memory_budget_bytes *= 2) {
      try {
        tight = render(s, col, rs);
        break;
      } catch (const std::runtime_error&) {
        ASSERT_LT(rs.memory_budget_bytes, uint64_t(1) << 30);
      }
    }
    EXPECT_TRUE(same_bits(tight, peel));
    EXPECT_GT(tight.stats.passes, sorted.stats.passes + tight.stats.tiles);
  }
}

}  // namespace
}  // namespace zs
