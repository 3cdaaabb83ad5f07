// In end_to_end/: it runs mesh readers, scene, the ZSweep engine and the reference together.
// Numerical stability at the extremes (issue 5): each case renders with the
// ZSweep engine and with the reference ray caster and asserts how far apart
// they may be — float rounding (1e-5) unless the case says otherwise.
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "output/image_compare.h"
#include "geometry/tets/default_mesh.h"
#include "geometry/tets/io/mesh_io.h"
#include "scene/scene.h"
#include "support/test_paths.h"
#include "geometry/tets/topology.h"
#include "render/reference/reference_renderer.h"
#include "support/test_meshes.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {
namespace {

using test::box_chord;
using test::box_mesh;
using test::spec_ray;

struct Both {
  Image z, ref;
  RenderStats zs;
  ReferenceStats rs;
  double diff() const { return compare_images(z, ref).max_abs; }
};

Both render_both(const TetMesh& m, const RenderSettings& rs) {
  const Topology topo = build_topology(m);
  Both b;
  b.z = render_zsweep(m, topo, rs, &b.zs);
  b.ref = render_reference(m, topo, rs, rs.tf, &b.rs);
  return b;
}

RenderSettings base_settings(uint32_t W, uint32_t H, TransferFunction tf) {
  RenderSettings rs;
  rs.width = W;
  rs.height = H;
  rs.camera.projection = Projection::Perspective;
  rs.camera.eye = {2.6, 1.6, 3.4};
  rs.camera.target = {0, 0, 0};
  rs.camera.up = {0, 1, 0};
  rs.camera.fov_y = 35;
  rs.camera.height = 2.6;
  rs.tf = std::move(tf);
  rs.threads = 2;
  return rs;
}

// The default scene's transfer function, with its unit distance scaled.
TransferFunction blob_tf(double unit) {
  return TransferFunction({{0.0, 0.1, 0.2, 0.6}, {0.3, 0.1, 0.7, 0.8}, {0.6, 0.95, 0.85, 0.3}, {1.0, 0.9, 0.2, 0.1}},
                          {{0.0, 0.0}, {0.15, 0.0}, {0.35, 0.08}, {0.6, 0.25}, {1.0, 0.8}}, unit);
}

// Coordinates offset by 1e6 and scaled by 1e-6 and 1e6, camera (and the
// transfer function's unit distance) transformed the same way: the same
// image within 1/255, and still within rounding of the reference.
TEST(Stability, OffsetAndScaleGiveTheSameImage) {
  const TetMesh m = default_mesh(10);
  for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
    RenderSettings rs = base_settings(96, 80, blob_tf(0.1));
    rs.camera.projection = proj;
    const Both plain = render_both(m, rs);
    EXPECT_LE(plain.diff(), 1e-5);
    struct Xf {
      const char* name;
      double scale;
      glm::dvec3 offset;
    };
    for (const Xf& x : {Xf{"offset 1e6", 1.0, {1e6, -1e6, 1e6}}, Xf{"scale 1e-6", 1e-6, {0, 0, 0}},
                        Xf{"scale 1e6", 1e6, {0, 0, 0}}, Xf{"scale 1e-6 + offset", 1e-6, {3e-6, 0, -2e-6}}}) {
      TetMesh t = m;
      for (auto& p : t.points) p = p * x.scale + x.offset;
      RenderSettings r2 = rs;
      r2.camera.eye = rs.camera.eye * x.scale + x.offset;
      r2.camera.target = rs.camera.target * x.scale + x.offset;
      r2.camera.height = rs.camera.height * x.scale;
      r2.tf = blob_tf(0.1 * x.scale);
      const Both b = render_both(t, r2);
      EXPECT_LE(compare_images(b.z, plain.z).max_abs, 1.0 / 255) << x.name << " " << int(proj);
      EXPECT_LE(b.diff(), 1e-5) << x.name << " " << int(proj);
      EXPECT_EQ(b.zs.tets_degenerate, 0u) << x.name;
    }
  }
}

// A square bipyramid whose middle tet is a sliver: the square's corner C is
// lifted by eps, so the sliver's smallest dihedral angle is about eps·sqrt 2
// radians (< 0.1° for eps = 1e-3).
TetMesh sliver_bipyramid(double eps) {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, eps}, {0, 1, 0}, {0.5, 0.5, 0.8}, {0.5, 0.5, -0.8}};
  m.scalars = {0.2, 0.9, 0.5, 0.7, 1.0, 0.0};
  enum { A, B, C, D, E, F };
  m.tets = {{A, B, C, D}, {E, A, B, C}, {E, A, C, D}, {F, A, B, D}, {F, B, C, D}};
  return m;
}

double min_dihedral_degrees(const TetMesh& m, const Tet& t) {
  double best = 180;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      int o[2], n = 0;
      for (int k = 0; k < 4; ++k)
        if (k != a && k != b) o[n++] = k;
      const glm::dvec3 p = m.points[t[a]], e = glm::normalize(m.points[t[b]] - p);
      auto perp = [&](int k) {
        const glm::dvec3 v = m.points[t[k]] - p;
        return glm::normalize(v - glm::dot(v, e) * e);
      };
      best = std::min(best, std::acos(std::clamp(glm::dot(perp(o[0]), perp(o[1])), -1.0, 1.0)) * 180 / M_PI);
    }
  return best;
}

TEST(Stability, SliversRenderLikeTheReference) {
  const TetMesh m = sliver_bipyramid(1e-3);
  ASSERT_LT(min_dihedral_degrees(m, m.tets[0]), 0.1);
  TransferFunction tf({{0, 0.9, 0.3, 0.1}, {1, 0.1, 0.4, 0.9}}, {{0, 0.2}, {0.5, 0.9}, {1, 0.4}}, 0.3);
  // Oblique, straight down onto the sliver, and exactly in its plane.
  for (glm::dvec3 eye : {glm::dvec3{2.1, 1.3, 2.7}, glm::dvec3{0.5, 0.5, 4.0}, glm::dvec3{4.0, 0.5, 0.0}})
    for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
      RenderSettings rs = base_settings(90, 70, tf);
      rs.camera.projection = proj;
      rs.camera.eye = eye;
      rs.camera.target = {0.5, 0.5, 0};
      rs.camera.height = 2.0;
      const Both b = render_both(m, rs);
      EXPECT_LE(b.diff(), 1e-5) << eye.x << "," << eye.y << "," << eye.z << " " << int(proj);
      EXPECT_GT(b.rs.rays_hit, 100u);
      EXPECT_EQ(b.rs.lost_walks, 0u);
    }
}

// A box whose x = 0 side is collapsed onto a line (as in the blunt fin's
// grid): the cells along it are flat, zero-volume tets with distinct vertex
// ids. They are counted and dropped; the image still matches the reference.
TEST(Stability, ZeroVolumeTetsAreCountedAndHarmless) {
  TetMesh m = box_mesh({6, 4, 4}, {0, -1, -1}, {2, 1, 1}, [](const glm::dvec3& p) { return 0.5 + 0.2 * p.x + 0.1 * p.z; });
  for (auto& p : m.points) p.y *= std::min(p.x, 1.0);  // x = 0: every y collapses to 0
  TransferFunction tf({{0, 0.2, 0.8, 0.3}, {1, 0.9, 0.5, 0.1}}, {{0, 0.1}, {1, 0.7}}, 0.5);
  for (glm::dvec3 eye : {glm::dvec3{-3.0, 0.4, 0.3}, glm::dvec3{1.0, 3.0, 2.5}}) {
    RenderSettings rs = base_settings(80, 64, tf);
    rs.camera.eye = eye;
    rs.camera.target = {0.8, 0, 0};
    const Both b = render_both(m, rs);
    EXPECT_GT(b.zs.tets_degenerate, 0u);
    EXPECT_LE(b.diff(), 1e-5) << eye.x;
    EXPECT_GT(b.rs.rays_hit, 500u);
  }
}

// Orthographic, looking straight down the grid: every x- and y-plane face is
// seen exactly edge-on and every vertex of a grid layer has the same depth.
// The grid sits on the pixel lattice — vertices on pixel corners, the
// 5-tet diagonals through pixel centres — and is sheared in z (which
// changes no projection) so the top and bottom faces are oblique.
TEST(Stability, EdgeOnFacesAndVerticesOnThePixelLattice) {
  const double a = 0.3, unit = 5.0, tau = -std::log(1 - a) / unit;
  for (double shift : {0.0, 0.5}) {  // 0: vertices on pixel corners; 0.5: on pixel centres
    TetMesh m = box_mesh({12, 10, 3}, {-12 + shift, -10 + shift, -2}, {12 + shift, 10 + shift, 2},
                         [](const glm::dvec3&) { return 1.0; });
    for (auto& p : m.points) p.z += 0.3 * p.x + 0.2 * p.y;
    RenderSettings rs = base_settings(64, 48, TransferFunction({{0, 1, 1, 1}}, {{0, a}}, unit));
    rs.camera.projection = Projection::Orthographic;
    rs.camera.eye = {0, 0, 50};
    rs.camera.target = {0, 0, 0};
    rs.camera.height = 48;  // one world unit per pixel: pixel centres at half-integers
    const Both b = render_both(m, rs);
    double worst = 0, worst_ref = 0;
    uint64_t on_silhouette = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        const double x = o.x - shift, y = o.y - shift;
        // (spec_ray's arithmetic puts lattice points within 1e-9 of integers.)
        auto on = [](double v, double e) { return std::abs(std::abs(v) - e) < 1e-9; };
        const bool edge = (on(x, 12) && std::abs(y) < 10 + 1e-9) || (on(y, 10) && std::abs(x) < 12 + 1e-9);
        const bool inside = !edge && std::abs(x) < 12 && std::abs(y) < 10;
        const double want = inside ? 1 - std::exp(-tau * 4.0) : 0.0;
        const double got = b.z.at(i, j)[3];
        if (edge) {
          // A ray exactly along the silhouette: the engine's tie rule takes
          // it on the left/top side only; either value is right.
          ++on_silhouette;
          const double full = 1 - std::exp(-tau * 4.0);
          EXPECT_TRUE(std::abs(got) < 1e-6 || std::abs(got - full) < 1e-5) << i << "," << j << " " << got;
          continue;
        }
        worst = std::max(worst, std::abs(got - want));
        worst_ref = std::max(worst_ref, std::abs(b.ref.at(i, j)[3] - want));
      }
    EXPECT_LE(worst, 1e-5) << shift;
    EXPECT_LE(worst_ref, 1e-5) << shift;
    // Pixel centres at x = i - 32 + 0.5 - shift: on the silhouette only when shifted.
    EXPECT_EQ(on_silhouette, shift == 0 ? 0u : 2u * 21 + 2u * 25 - 4u) << shift;
    EXPECT_EQ(b.zs.faces_degenerate > 0, true) << "edge-on faces project to zero area";
  }
}

// Two boxes sharing a face with separate vertices (a seam of coincident
// boundary faces, as in the post's O-grid): the same image as one box.
TEST(Stability, CoincidentFacesAreASeamNotAGap) {
  const double a = 0.5, unit = 1.0, tau = -std::log(1 - a) / unit;
  auto one = [](const glm::dvec3&) { return 1.0; };
  const glm::dvec3 lo{-1, -0.8, -0.6}, mid{0.1, 0.8, 0.6}, hi{1, 0.8, 0.6};
  TetMesh m = box_mesh({4, 3, 3}, lo, mid, one);
  test::append_mesh(m, box_mesh({3, 4, 2}, {0.1, -0.8, -0.6}, hi, one));  // different grid: faces do not match up
  for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
    RenderSettings rs = base_settings(80, 60, TransferFunction({{0, 1, 1, 1}}, {{0, a}}, unit));
    rs.camera.projection = proj;
    rs.camera.eye = {3.1, 1.2, 2.0};
    rs.camera.target = {0, 0, 0};
    const Both b = render_both(m, rs);
    double worst = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        worst = std::max(worst, std::abs(b.z.at(i, j)[3] - (1 - std::exp(-tau * box_chord(o, d, lo, hi)))));
      }
    EXPECT_LE(worst, 1e-5) << int(proj);
    EXPECT_LE(b.diff(), 1e-5) << int(proj);
  }
}

// A long thin stack seen end-on: more than 1000 fragments per pixel.
TEST(Stability, DepthComplexityOverAThousand) {
  const glm::dvec3 lo{-0.5, -0.5, -200}, hi{0.5, 0.5, 200};
  const TetMesh m = box_mesh({1, 1, 400}, lo, hi, [](const glm::dvec3& p) { return 0.5 + 0.002 * p.z; });
  TransferFunction tf({{0, 0.2, 0.4, 1.0}, {1, 1.0, 0.4, 0.2}}, {{0, 0.0}, {0.5, 0.01}, {1, 0.002}}, 1.0);
  RenderSettings rs = base_settings(24, 24, tf);
  rs.camera.projection = Projection::Orthographic;
  rs.camera.eye = {0.013, 0.021, 300};
  rs.camera.target = {0.013, 0.021, 0};
  rs.camera.up = {0.1, 1, 0};
  rs.camera.height = 1.2;
  const Both b = render_both(m, rs);
  // Lists stay short (delayed compositing), but each pixel sees > 1000 fragments.
  EXPECT_GT(b.zs.fragments, 1000u * b.zs.rendered_pixels);
  EXPECT_GT(b.zs.rendered_pixels, 100u);
  EXPECT_LE(b.diff(), 1e-5);
  // Cross-check one central ray with fine quadrature.
  double q[4];
  glm::dvec3 o, d;
  spec_ray(rs.camera, 24, 24, 12, 12, &o, &d);
  test::march_box_ray(tf, [](const glm::dvec3& p) { return 0.5 + 0.002 * p.z; }, o, d, lo, hi, q);
  EXPECT_NEAR(b.z.at(12, 12)[3], q[3], 1e-5);
}

// Opacity jumping from 0 to 0.999 over 1e-6 of the scalar range, opacity
// exactly 0 (everything culled, background untouched) and exactly 1.
TEST(Stability, NearStepAndExtremeOpacities) {
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.3 * p.x - 0.2 * p.y + 0.1 * p.z; };
  const glm::dvec3 lo{-1, -1, -1}, hi{1, 1, 1};
  const TetMesh m = box_mesh({5, 5, 5}, lo, hi, field);
  {
    TransferFunction step({{0, 0.2, 0.9, 0.4}, {1, 0.9, 0.1, 0.3}}, {{0.5, 0.0}, {0.5 + 1e-6, 0.999}}, 0.5);
    RenderSettings rs = base_settings(72, 60, step);
    const Both b = render_both(m, rs);
    EXPECT_LE(b.diff(), 1e-5);
    double worst = 0;
    for (uint32_t j = 0; j < 60; j += 3)
      for (uint32_t i = 0; i < 72; i += 3) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, 72, 60, int(i), int(j), &o, &d);
        double q[4];
        test::march_box_ray(step, field, o, d, lo, hi, q);
        worst = std::max(worst, std::abs(b.ref.at(i, j)[3] - q[3]));
      }
    EXPECT_LE(worst, 2e-3) << "reference vs 20,000-step marching (the marcher resolves the step to one step)";
  }
  {
    RenderSettings rs = base_settings(40, 30, TransferFunction({{0, 1, 0, 0}}, {{0, 0.0}}, 1.0));
    rs.background[2] = 0.25;
    rs.background[3] = 0.5;
    const Both b = render_both(m, rs);
    EXPECT_EQ(b.zs.tets_invisible, m.num_tets());
    EXPECT_EQ(b.zs.fragments, 0u);
    for (size_t k = 0; k < b.z.rgba.size(); ++k) EXPECT_EQ(b.z.rgba[k], b.ref.rgba[k]);
    EXPECT_EQ(b.z.at(20, 15)[3], 0.5f);
  }
  {
    const double c[3] = {0.3, 0.6, 0.9};
    RenderSettings rs = base_settings(40, 30, TransferFunction({{0, c[0], c[1], c[2]}}, {{0, 1.0}}, 1e-3));
    const Both b = render_both(m, rs);
    EXPECT_LE(b.diff(), 1e-5);
    // Opaque: covered pixels carry the colour itself.
    uint64_t covered = 0;
    for (uint32_t j = 0; j < 30; ++j)
      for (uint32_t i = 0; i < 40; ++i)
        if (b.ref.at(i, j)[3] > 0.999) {
          ++covered;
          for (int k = 0; k < 3; ++k) EXPECT_NEAR(b.z.at(i, j)[k], c[k], 1e-5);
        }
    EXPECT_GT(covered, 300u);
  }
}

// Scalar NaN at some vertices: the cells touching them are empty, in both
// renderers, and nothing else changes.
TEST(Stability, NaNScalarsMakeTheirCellsEmpty) {
  TetMesh m = box_mesh({4, 4, 4}, {-1, -1, -1}, {1, 1, 1}, [](const glm::dvec3& p) { return 0.5 + 0.3 * p.x; });
  size_t nan_points = 0;
  for (size_t v = 0; v < m.points.size(); v += 7) m.scalars[v] = std::numeric_limits<double>::quiet_NaN(), ++nan_points;
  RenderSettings rs = base_settings(64, 48, TransferFunction({{0, 0.2, 0.5, 0.9}, {1, 0.9, 0.5, 0.2}}, {{0, 0.3}, {1, 0.6}}, 0.7));
  const Both b = render_both(m, rs);
  EXPECT_GT(b.zs.tets_degenerate, 0u);
  EXPECT_LE(b.diff(), 1e-5);
  for (float v : b.z.rgba) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(b.rs.rays_hit, 500u);
}

// 1×1, 1×N and N×1 images: the one pixel (or line) is the reference's.
TEST(Stability, TinyAndDegenerateImageShapes) {
  const TetMesh m = default_mesh(8);
  for (auto [w, h] : {std::pair{1u, 1u}, std::pair{1u, 97u}, std::pair{97u, 1u}, std::pair{2u, 3u}})
    for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
      RenderSettings rs = base_settings(w, h, blob_tf(0.1));
      rs.camera.projection = proj;
      rs.camera.eye = {0.3, 0.2, 3.0};
      rs.camera.target = {0.01, -0.02, 0};
      const Both b = render_both(m, rs);
      EXPECT_LE(b.diff(), 1e-5) << w << "x" << h;
      EXPECT_GT(b.rs.rays_hit, 0u) << w << "x" << h;
    }
}

// Perspective from inside a real-looking mesh (the default ball of blobs),
// looking several ways: only what is in front of the eye is integrated.
TEST(Stability, EyeInsideTheMesh) {
  const TetMesh m = default_mesh(12);
  for (glm::dvec3 target : {glm::dvec3{1, 0.2, 0.1}, glm::dvec3{-0.3, -1, 0.4}, glm::dvec3{0.05, 0.1, -1}}) {
    RenderSettings rs = base_settings(72, 54, blob_tf(0.1));
    rs.camera.eye = {0.11, 0.07, -0.05};
    rs.camera.target = target;
    rs.camera.fov_y = 80;
    const Both b = render_both(m, rs);
    EXPECT_GT(b.zs.faces_clipped, 0u);
    EXPECT_EQ(b.rs.rays_hit, 72u * 54u);
    EXPECT_LE(b.diff(), 1e-5) << target.x;
  }
}

}  // namespace
}  // namespace zs

namespace zs {
namespace {

// Compares sampled rows of a tile-rendered image with reference rows, without
// ever holding the full image.
struct SampledRows : TileSink {
  std::vector<uint32_t> rows;
  Image ref;  // row k = image row rows[k]
  double max_diff = 0;
  uint64_t compared_pixels = 0;
  void tile(const TileRect& t, const float* rgba) override {
    for (size_t k = 0; k < rows.size(); ++k) {
      if (rows[k] < t.y0 || rows[k] >= t.y1) continue;
      const float* got = rgba + size_t(rows[k] - t.y0) * t.width() * 4;
      const float* want = ref.at(t.x0, uint32_t(k));
      for (size_t q = 0; q < size_t(t.width()) * 4; ++q) max_diff = std::max(max_diff, double(std::abs(got[q] - want[q])));
      compared_pixels += t.width();
    }
  }
};

// 16384² and 32768² renders of spx within a 768 MiB budget: rows sampled
// across the mesh match the reference, and the process's peak memory stays
// within the budget (plus 160 MiB for the program, mesh and reference rows).
// Slow on purpose: the whole image is rendered, tile by tile, into a sink
// that keeps only the sampled rows.
void huge_spx(const std::string& path, uint32_t size) {
  const TetMesh m = read_mesh(path);
  const Topology topo = build_topology(m);
  {
    RenderSettings rs;
    rs.width = rs.height = size;
    rs.camera = auto_camera(m, Projection::Perspective, size, size);
    rs.tf = default_transfer_function(m);
    rs.threads = 2;
    rs.memory_budget_bytes = uint64_t(768) << 20;
    SampledRows sink;
    for (uint32_t k = 1; k < 24; ++k) sink.rows.push_back(uint32_t(uint64_t(size) * k / 24) + k % 3);
    ReferenceStats rst;
    sink.ref = render_reference_rows(m, topo, rs, rs.tf, sink.rows, &rst);
    RenderStats st;
    render_zsweep_tiles(m, topo, rs, sink, 0, &st);
    EXPECT_EQ(sink.compared_pixels, uint64_t(sink.rows.size()) * size) << size;
    EXPECT_LE(sink.max_diff, 1e-5) << size;
    EXPECT_GT(rst.rays_hit, uint64_t(size) * 2) << size;
    EXPECT_GT(st.tiles, 1u);
    EXPECT_LE(st.peak_rss_bytes, rs.memory_budget_bytes + (uint64_t(160) << 20)) << size;
    std::printf("%u²: %llu tiles, peak RSS %.0f MiB, %.1f s, max diff %.2g over %zu rows\n", size,
                (unsigned long long)st.tiles, st.peak_rss_bytes / 1048576.0, st.ms_total / 1000, sink.max_diff,
                sink.rows.size());
  }
}

TEST(Stability, Huge16384OfSpxWithinABudget) {
  ZS_REQUIRE_SHARED(path, "spx.off");
  huge_spx(path, 16384);
}
TEST(Stability, Huge32768OfSpxWithinABudget) {
  ZS_REQUIRE_SHARED(path, "spx.off");
  huge_spx(path, 32768);
}

}  // namespace
}  // namespace zs
