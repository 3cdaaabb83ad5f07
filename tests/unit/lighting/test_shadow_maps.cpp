// The shadow-map module (src/lighting/): the digest's step-edge table, level
// counts of PCF(k, n), the fixed patterns, the bias on tilted receivers.
#include <cfloat>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lighting/depth_blocks.h"
#include "lighting/multi_depth.h"
#include "lighting/tiled_depths.h"
#include "lighting/shadow_map.h"

namespace zs {
namespace {

// An orthographic map of D×D unit texels looking along +z: texel (i, j)'s
// centre is the world point texel_point(i, j, depth).
constexpr uint32_t D = 32;
Camera map_frame() {
  Camera c;
  c.projection = Projection::Orthographic;
  c.eye = {0, 0, 0};
  c.target = {0, 0, 1};
  c.up = {0, 1, 0};
  c.height = D;
  return c;
}
Light down_z() {
  Light l;
  l.type = LightType::Directional;
  l.direction = {0, 0, 1};
  return l;
}
glm::dvec3 point_at(const View& v, double X, double Y, double depth) {
  glm::dvec3 o, d;
  v.ray(X, Y, &o, &d);
  return o + d * depth;
}
const glm::dvec3 kFacing{0, 0, -1};  // a receiver facing the light

ShadowSettings settings(uint32_t depths, DepthSelect sel, uint32_t pcf, double bias = 0.1) {
  ShadowSettings s;
  s.depths = depths;
  s.select = sel;
  s.pcf = pcf;
  s.bias = bias;
  s.slope_bias = 0;
  return s;
}

// Occluder at depth O over the columns x <= 15, receiver at R elsewhere.
constexpr float O = 1.0f, R = 2.0f;
std::vector<float> step_map() {
  std::vector<float> z(D * D);
  for (uint32_t y = 0; y < D; ++y)
    for (uint32_t x = 0; x < D; ++x) z[y * D + x] = x <= 15 ? O : R;
  return z;
}

// The shadow-maps digest §2.6.5 table: the receiver's lit fraction at cells −2, −1, 0, +1
// of the edge (cells 14, 15, 16, 17 here), for 1-SM, 2-SM max/min, 3-SM.
TEST(ShadowMaps, StepEdgeTableExactly) {
  struct Row {
    uint32_t n;
    DepthSelect sel;
    double lit[4];
  };
  const Row rows[] = {
      {1, DepthSelect::Max, {0, 0, 1, 1}},
      {2, DepthSelect::Max, {0, 0.5, 1, 1}},
      {2, DepthSelect::Min, {0, 0, 0.5, 1}},
      {3, DepthSelect::Max, {0, 1.0 / 3, 2.0 / 3, 1}},
  };
  for (const Row& r : rows) {
    const ShadowMap m = ShadowMap::from_depths(down_z(), map_frame(), D, step_map(), settings(r.n, r.sel, 1));
    for (int c = 0; c < 4; ++c) {
      const glm::dvec3 p = point_at(m.view(), 14 + c, 10, R);
      EXPECT_DOUBLE_EQ(m.lit(p, kFacing), r.lit[c]) << r.n << "-SM " << to_string(r.sel) << " cell " << c - 2;
    }
    // The occluder's own top stays lit under every rule but min (its
    // neighbourhood's minimum is itself; max-selected values are >= it).
    const glm::dvec3 top = point_at(m.view(), 15, 10, O);
    EXPECT_DOUBLE_EQ(m.lit(top, kFacing), 1.0) << r.n << "-SM " << to_string(r.sel);
  }
}

TEST(ShadowMaps, MultiDepthPassKeepsCentreFirstAndSelects) {
  std::vector<float> z(D * D);
  for (uint32_t i = 0; i < z.size(); ++i) z[i] = float((i * 7919) % 101);
  for (uint32_t n : {2u, 3u, 4u, 5u, 9u}) {
    std::vector<float> out(z.size() * n);
    build_multi_depth(z.data(), D, n, DepthSelect::Max, out.data());
    for (uint32_t y = 1; y + 1 < D; ++y)
      for (uint32_t x = 1; x + 1 < D; ++x) {
        const float* o = &out[(y * D + x) * n];
        EXPECT_EQ(o[0], z[y * D + x]);
        float mx = -1, mn = 1e9;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            mx = std::max(mx, z[(y + dy) * D + x + dx]);
            mn = std::min(mn, z[(y + dy) * D + x + dx]);
          }
        if (n == 2) EXPECT_EQ(o[1], mx);
        if (n == 3) {
          EXPECT_EQ(o[1], mx);
          EXPECT_EQ(o[2], mn);
        }
        if (n >= 4) {
          const auto pat = depth_pattern(n);
          for (uint32_t i = 0; i + 1 < n; ++i) EXPECT_EQ(o[i + 1], z[(y + pat[i].second) * D + x + pat[i].first]);
        }
      }
  }
  // The patterns: n − 1 distinct neighbours, one texel away.
  for (uint32_t n = 4; n <= kMaxDepths; ++n) {
    const auto pat = depth_pattern(n);
    std::set<std::pair<int, int>> distinct(pat.begin(), pat.end());
    EXPECT_EQ(distinct.size(), n - 1) << n;
    for (auto [dx, dy] : pat) EXPECT_EQ(std::max(std::abs(dx), std::abs(dy)), 1) << n;
  }
}

// Every PCF(k, n) gives at most n·k + 1 distinct lit values, and reaches
// it on a map with a round occluder and thin bars. A single straight edge is
// not enough for n >= 2 with a 2×2 kernel: in a 2×2 window every texel
// neighbours every other, so once a lit texel is in the window every
// occluded one is a band texel (value 1 of 2 under max), and sums such as
// 4 of 8 for PCF(4, 2) need an occluder thinner than the window.
TEST(ShadowMaps, LevelCountsReachNkPlusOne) {
  std::vector<float> z(D * D);
  for (uint32_t y = 0; y < D; ++y)
    for (uint32_t x = 0; x < D; ++x)
      z[y * D + x] = std::hypot(x - 12.3, y - 16.1) < 7.7 || (x >= 25 && x <= 26) || (y >= 27 && y <= 29) ||
                             (x == 29 && y < 20) ? O : R;
  struct Cfg {
    uint32_t n, k;
    DepthSelect sel;
  };
  const Cfg cfgs[] = {{1, 1, DepthSelect::Max},  {2, 1, DepthSelect::Max}, {2, 1, DepthSelect::Min},
                      {3, 1, DepthSelect::Max},  {1, 4, DepthSelect::Max}, {1, 9, DepthSelect::Max},
                      {1, 16, DepthSelect::Max}, {2, 4, DepthSelect::Max}, {2, 9, DepthSelect::Max},
                      {3, 4, DepthSelect::Max},  {3, 9, DepthSelect::Max}, {4, 4, DepthSelect::Max}};
  for (const Cfg& c : cfgs) {
    const ShadowMap m = ShadowMap::from_depths(down_z(), map_frame(), D, z, settings(c.n, c.sel, c.k));
    std::set<uint32_t> seen;
    for (double Y = 2; Y < D - 1; Y += 0.25)
      for (double X = 2; X < D - 1; X += 0.25) seen.insert(m.lit_count(point_at(m.view(), X, Y, R), kFacing));
    EXPECT_EQ(m.levels(), c.n * c.k);
    EXPECT_LE(seen.size(), c.n * c.k + 1) << "PCF(" << c.k << "," << c.n << ")";
    std::string lv;
    for (uint32_t v : seen) lv += std::to_string(v) + " ";
    EXPECT_EQ(seen.size(), c.n * c.k + 1) << "PCF(" << c.k << "," << c.n << "): " << lv;
  }
}

// A receiver tilted against the light: the default slope bias keeps every
// configuration free of self-shadowing; without it the min-selected and
// wide-kernel tests shadow the plane itself.
TEST(ShadowMaps, TiltedPlaneHasNoAcneAtTheDefaultBias) {
  for (double deg : {20.0, 45.0, 70.0, 80.0}) {
    const double t = std::tan(deg * M_PI / 180);
    // Plane depth = 5 + t·x (x in world units along the map's X).
    const Camera cam = map_frame();
    const View v(cam, D, D);
    std::vector<float> z(D * D);
    for (uint32_t y = 0; y < D; ++y)
      for (uint32_t x = 0; x < D; ++x) {
        const glm::dvec3 p = point_at(v, x, y, 0);
        const double d = 5 + t * p.x;
        float f = float(d);
        if (double(f) < d) f = std::nextafter(f, INFINITY);
        z[y * D + x] = f;
      }
    const glm::dvec3 n = glm::normalize(glm::dvec3(t, 0, -1));  // facing the light
    for (uint32_t depths : {1u, 2u, 3u, 4u})
      for (DepthSelect sel : {DepthSelect::Max, DepthSelect::Min})
        for (uint32_t k : {1u, 4u, 9u, 16u}) {
          ShadowSettings s;  // default bias and slope bias
          s.depths = depths;
          s.select = sel;
          s.pcf = k;
          const ShadowMap m = ShadowMap::from_depths(down_z(), cam, D, z, s);
          s.slope_bias = 0;
          const ShadowMap unbiased = ShadowMap::from_depths(down_z(), cam, D, z, s);
          uint32_t acne = 0, acne_unbiased = 0;
          for (double Y = 4; Y < D - 4; Y += 0.37)
            for (double X = 4; X < D - 4; X += 0.37) {
              const glm::dvec3 q = point_at(v, X, Y, 0);
              const glm::dvec3 p = point_at(v, X, Y, 5 + t * q.x);
              acne += m.lit_count(p, n) != m.levels();
              acne_unbiased += unbiased.lit_count(p, n) != unbiased.levels();
            }
          EXPECT_EQ(acne, 0u) << deg << " deg, " << depths << "-SM " << to_string(sel) << ", PCF " << k;
          if (k > 1 || depths >= 3 || (depths == 2 && sel == DepthSelect::Min))
            EXPECT_GT(acne_unbiased, 0u) << deg << " deg, " << depths << "-SM " << to_string(sel) << ", PCF " << k;
        }
  }
}

// Empty texels (+inf) never shadow; a point facing away is unlit; a spot
// light reaches nothing outside its cone.
TEST(ShadowMaps, EmptyTexelsFacingAndCone) {
  const ShadowMap m = ShadowMap::from_depths(down_z(), map_frame(), D, std::vector<float>(D * D, INFINITY),
                                             settings(3, DepthSelect::Max, 9));
  const glm::dvec3 p = point_at(m.view(), 10, 10, 4);
  EXPECT_EQ(m.lit_count(p, kFacing), m.levels());
  EXPECT_EQ(m.lit_count(p, -kFacing), 0u);
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0, 0, 0};
  spot.target = {0, 0, 1};
  spot.fov_deg = 60;
  EXPECT_TRUE(in_light_cone(spot, {0.5, 0, 1}));   // 26.6° off the axis
  EXPECT_FALSE(in_light_cone(spot, {0.6, 0, 1}));  // 31.0°
  EXPECT_FALSE(in_light_cone(spot, {0, 0, 0}));
}

// The block ranges bound every texel of the blocks they cover, exactly.
TEST(ShadowMaps, DepthBlocksBoundTheirTexels) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0, 10);
  const uint32_t S = 45;  // not a multiple of the block size
  std::vector<float> z(S * S);
  for (float& v : z) v = U(rng) < 2 ? INFINITY : U(rng);
  DepthBlocks b;
  b.reset(S);
  fold_block_ranges(z.data(), S, 0, 0, S, S, b);
  EXPECT_EQ(b.blocks, 6u);
  for (int t = 0; t < 300; ++t) {
    int x0 = int(rng() % S), x1 = int(rng() % S), y0 = int(rng() % S), y1 = int(rng() % S);
    if (x0 > x1) std::swap(x0, x1);
    if (y0 > y1) std::swap(y0, y1);
    float lo, hi, m = INFINITY, M = -INFINITY;
    b.range(x0, y0, x1, y1, &lo, &hi);
    // The exact range of the whole blocks the rectangle touches.
    for (uint32_t y = uint32_t(y0 / 8) * 8; y < std::min(S, uint32_t(y1 / 8 + 1) * 8); ++y)
      for (uint32_t x = uint32_t(x0 / 8) * 8; x < std::min(S, uint32_t(x1 / 8 + 1) * 8); ++x) {
        m = std::min(m, z[y * S + x]);
        M = std::max(M, z[y * S + x]);
      }
    ASSERT_EQ(lo, m);
    ASSERT_EQ(hi, M);
  }
  // Dilation: each block's range covers its 3×3 blocks.
  DepthBlocks d = b;
  dilate_block_ranges(d);
  for (uint32_t y = 0; y < 6; ++y)
    for (uint32_t x = 0; x < 6; ++x)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const int yy = int(y) + j, xx = int(x) + i;
          if (yy < 0 || xx < 0 || yy >= 6 || xx >= 6) continue;
          EXPECT_LE(d.min[y * 6 + x], b.min[yy * 6 + xx]);
          EXPECT_GE(d.max[y * 6 + x], b.max[yy * 6 + xx]);
        }
}

// The blocks' early outs (fully lit, fully shadowed) and the batch give the
// counts of reading every kernel texel and depth, for every configuration.
TEST(ShadowMaps, EarlyOutsAndBatchGiveTheDirectCounts) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  // Rectangles of casters at assorted depths over an empty (+inf) map.
  std::vector<float> z(D * D, INFINITY);
  for (int r = 0; r < 12; ++r) {
    const uint32_t x0 = rng() % D, y0 = rng() % D, w = 1 + rng() % 12, h = 1 + rng() % 12;
    const float depth = float(1 + 4 * U(rng));
    for (uint32_t y = y0; y < std::min(D, y0 + h); ++y)
      for (uint32_t x = x0; x < std::min(D, x0 + w); ++x) z[y * D + x] = std::min(z[y * D + x], depth);
  }
  const View v(map_frame(), D, D);
  struct Config {
    uint32_t n;
    DepthSelect sel;
  };
  for (Config c : {Config{1, DepthSelect::Max}, Config{2, DepthSelect::Max}, Config{2, DepthSelect::Min},
                   Config{3, DepthSelect::Max}, Config{4, DepthSelect::Max}})
    for (uint32_t k : {1u, 4u, 9u, 16u}) {
      const ShadowMap m = ShadowMap::from_depths(down_z(), map_frame(), D, z, settings(c.n, c.sel, k, 0.01));
      const int w = k == 16 ? 4 : k == 9 ? 3 : k == 4 ? 2 : 1, first = k == 1 || k == 4 ? 0 : -1;
      const bool odd = k == 1 || k == 9;
      std::vector<double> px, py, pz, nx, ny, nz;
      std::vector<uint32_t> direct;
      for (int t = 0; t < 2000; ++t) {
        const double X = -3 + (D + 6) * U(rng), Y = -3 + (D + 6) * U(rng), depth = 6 * U(rng);
        const glm::dvec3 p = point_at(v, X, Y, depth);
        // Every read, as shadow_map.h defines the test.
        const ViewPoint q = v.project(p);
        const double lim = q.z - m.bias_at(p, kFacing);
        const double Xc = std::clamp(q.x, -8.0, D + 8.0), Yc = std::clamp(q.y, -8.0, D + 8.0);
        const int bx = int(odd ? std::floor(Xc + 0.5) : std::floor(Xc)) + first;
        const int by = int(odd ? std::floor(Yc + 0.5) : std::floor(Yc)) + first;
        uint32_t lit = 0;
        for (int dy = 0; dy < w; ++dy)
          for (int dx = 0; dx < w; ++dx)
            for (uint32_t j = 0; j < m.depths(); ++j)
              lit += lim <= double(m.depth(uint32_t(std::clamp(bx + dx, 0, int(D) - 1)),
                                           uint32_t(std::clamp(by + dy, 0, int(D) - 1)), j));
        ASSERT_EQ(m.lit_count(p, kFacing), lit) << "n " << c.n << " k " << k << " at " << X << "," << Y;
        px.push_back(p.x), py.push_back(p.y), pz.push_back(p.z);
        nx.push_back(kFacing.x), ny.push_back(kFacing.y), nz.push_back(kFacing.z);
        direct.push_back(lit);
      }
      std::vector<uint32_t> batch(direct.size());
      m.lit_counts(direct.size(), px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), batch.data());
      EXPECT_EQ(batch, direct);
      // The same tests from the affine lookup (what the surface renderer
      // composes with its view): column, row and limit from p.
      const AffineLookup A = m.affine_lookup();
      const double fb = m.face_bias(glm::dot(kFacing, -down_z().direction));
      std::vector<double> X, Y, lim;
      for (size_t i = 0; i < px.size(); ++i) {
        const glm::dvec3 p(px[i], py[i], pz[i]);
        X.push_back(A.x0 + glm::dot(A.x, p)), Y.push_back(A.y0 + glm::dot(A.y, p));
        const double zl = A.z0 + glm::dot(A.z, p);
        lim.push_back(zl - (fb + std::abs(zl) * 0x1p-20));
      }
      std::vector<uint32_t> affine(direct.size());
      m.counts_at(direct.size(), X.data(), Y.data(), lim.data(), affine.data());
      EXPECT_EQ(affine, direct) << "n " << c.n << " k " << k;
    }
  // A face turned from the light has no bias: none of its tests pass.
  const ShadowMap m = ShadowMap::from_depths(down_z(), map_frame(), D, z, settings(1, DepthSelect::Max, 1, 0.01));
  EXPECT_TRUE(std::isnan(m.face_bias(0.0)));
  EXPECT_TRUE(std::isnan(m.face_bias(-0.5)));
  const double X = 1, Y = 1, lim = NAN;
  uint32_t out = 7;
  m.counts_at(1, &X, &Y, &lim, &out);
  EXPECT_EQ(out, 0u);
}

// round_depths_up is float(z) moved one ulp up where it fell below z, bit
// for bit (it works on the bits so that it vectorizes).
TEST(ShadowMaps, DepthsRoundUpLikeNextafter) {
  std::vector<double> z = {0.0, -0.0, 1e-320, -1e-320, 1e-46, -1e-46, 1.4e-45, -1.4e-45, 1.0, -1.0, 0.1, -0.1,
                           double(FLT_MAX), -double(FLT_MAX), double(FLT_MAX) * (1 + 1e-12),
                           -double(FLT_MAX) * (1 + 1e-12), 1e39, -1e39, INFINITY, -INFINITY, NAN,
                           double(FLT_MIN), double(FLT_MIN) * (1 - 1e-9), -double(FLT_MIN) * (1 - 1e-9)};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int i = 0; i < 4000; ++i) z.push_back(U(rng) * std::pow(10.0, 40 * U(rng)));
  std::vector<float> out(z.size());
  const uint64_t covered = round_depths_up(z.data(), z.size(), out.data());
  uint64_t want_covered = 0;
  for (size_t i = 0; i < z.size(); ++i) {
    float f = float(z[i]);
    if (double(f) < z[i]) f = std::nextafter(f, INFINITY);
    uint32_t a, b;
    std::memcpy(&a, &out[i], 4), std::memcpy(&b, &f, 4);
    EXPECT_EQ(a, b) << "z " << z[i];
    want_covered += z[i] < INFINITY;
  }
  EXPECT_EQ(covered, want_covered);
}

// The tiled n-SM gives build_multi_depth's dense result at every texel: empty
// tiles, partial edge tiles and tiles that only border a caster included.
TEST(ShadowMaps, TiledMultiDepthEqualsTheDensePass) {
  std::mt19937 rng(5);
  const uint32_t S = 150;  // 3 × 3 tiles, the last ones partial
  std::vector<float> z(S * S, INFINITY);
  for (uint32_t y = 60; y < 70; ++y)  // straddles tile borders
    for (uint32_t x = 0; x < 130; ++x) z[y * S + x] = float(1 + (rng() % 100) / 10.0);
  z[149 * S + 149] = 3.f;  // the far corner texel
  TiledDepths centre;
  tile_depths(z.data(), S, &centre);
  EXPECT_EQ(centre.stored_tiles(), 7u);  // tile rows 0 and 1 × columns 0..2 hold the band; (2, 2) the corner
  for (uint32_t n : {2u, 3u, 4u, 5u, 9u})
    for (DepthSelect sel : {DepthSelect::Max, DepthSelect::Min}) {
      std::vector<float> dense(size_t(S) * S * n);
      build_multi_depth(z.data(), S, n, sel, dense.data());
      TiledDepths tiled;
      tiled_multi_depth(centre, n, sel, &tiled);
      EXPECT_EQ(tiled.stored_tiles(), 9u);
      for (uint32_t y = 0; y < S; ++y)
        for (uint32_t x = 0; x < S; ++x)
          for (uint32_t j = 0; j < n; ++j)
            ASSERT_EQ(tiled.texel(x, y)[j], dense[(size_t(y) * S + x) * n + j]) << n << " " << x << "," << y << "," << j;
    }
}

// ShadowMap::passes_all, the early out of lookups that fall in map tiles
// with no caster: exact at the tile border for each kernel, and every
// lookup inside a range it passes counts all levels (0 for a NaN limit).
TEST(ShadowMaps, EmptyTilesPassEveryTestInTheirRange) {
  constexpr uint32_t S = 512;  // 8 × 8 tiles of 64 texels
  Camera frame = map_frame();
  frame.height = S;
  // One caster block in tile (4, 4): texels 260..300 × 270..280.
  std::vector<float> z(size_t(S) * S, INFINITY);
  for (uint32_t y = 270; y <= 280; ++y)
    for (uint32_t x = 260; x <= 300; ++x) z[size_t(y) * S + x] = 1.5f;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  for (uint32_t n : {1u, 2u, 3u})
    for (uint32_t k : {1u, 4u, 9u, 16u}) {
      const ShadowMap m = ShadowMap::from_depths(down_z(), frame, S, z, settings(n, DepthSelect::Max, k, 0.01));
      // The last X whose kernel stays left of texel 256 (tile 4), and the
      // first that reaches it, rows inside the caster's tile row.
      const double last = k == 1 ? 255.49 : k == 4 ? 254.99 : k == 9 ? 254.49 : 253.99;
      const double first = k == 1 ? 255.5 : k == 4 ? 255.0 : k == 9 ? 254.5 : 254.0;
      if (n == 1) {  // an n-SM also stores the tiles around a caster's
        EXPECT_TRUE(m.passes_all(200, last, 262, 300)) << "k " << k;
        EXPECT_FALSE(m.passes_all(200, first, 262, 300)) << "k " << k;
      }
      EXPECT_TRUE(m.passes_all(-50, 120, -3, 100));  // tiles (0..1, 0..1), and off the map's corner
      EXPECT_FALSE(m.passes_all(-50, 120, -3, NAN));
      EXPECT_FALSE(m.passes_all(120, -50, -3, 100));  // an empty range
      EXPECT_FALSE(m.passes_all(0, S, 0, S));
      // Random ranges: where they pass, every lookup in them counts all levels.
      int passed = 0;
      for (int t = 0; t < 300; ++t) {
        double x0 = -20 + (S + 40) * U(rng), y0 = -20 + (S + 40) * U(rng);
        const double x1 = x0 + 100 * U(rng), y1 = y0 + 100 * U(rng);
        if (!m.passes_all(x0, x1, y0, y1)) continue;
        ++passed;
        std::vector<double> X, Y, lim;
        for (int i = 0; i < 64; ++i) {
          X.push_back(x0 + (x1 - x0) * U(rng)), Y.push_back(y0 + (y1 - y0) * U(rng));
          lim.push_back(i % 16 == 0 ? NAN : 10 * U(rng));
        }
        X[1] = x0, X[2] = x1, Y[3] = y0, Y[4] = y1;  // the corners themselves
        std::vector<uint32_t> out(X.size());
        m.counts_at(X.size(), X.data(), Y.data(), lim.data(), out.data());
        for (size_t i = 0; i < out.size(); ++i)
          ASSERT_EQ(out[i], lim[i] == lim[i] ? m.levels() : 0u) << "n " << n << " k " << k << " at " << X[i] << "," << Y[i];
      }
      EXPECT_GT(passed, 100);
    }
}

}  // namespace
}  // namespace zs
