// The reference ray caster against closed forms and fine quadrature — it is
// the ground truth for every error figure, so it is checked first on its own.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "geometry/tets/topology.h"
#include "render/reference/boundary_hits.h"
#include "render/reference/reference_renderer.h"
#include "support/test_meshes.h"

namespace zs {
namespace {

using test::box_chord;
using test::box_mesh;
using test::spec_ray;

RenderSettings ref_settings(uint32_t W, uint32_t H, Projection proj, TransferFunction tf) {
  RenderSettings rs = test::settings(W, H, proj, std::move(tf));
  rs.threads = 2;
  return rs;
}

Image reference(const TetMesh& m, const RenderSettings& rs, ReferenceStats* st) {
  return render_reference(m, build_topology(m), rs, rs.tf, st);
}

TEST(Reference, WatertightAtSharedEdgesAndVertices) {
  // A fan of 8 triangles around a centre vertex in the z = 0 plane: lines
  // through the centre and through points along each spoke (shared edges) each hit
  // at least one triangle.
  std::vector<glm::dvec3> rim;
  for (int k = 0; k < 8; ++k) rim.push_back({std::cos(k * M_PI / 4 + 0.1), std::sin(k * M_PI / 4 + 0.1), 0.0});
  const glm::dvec3 c{0.0, 0.0, 0.0};
  auto count_hits = [&](glm::dvec3 p) {
    int n = 0;
    for (int k = 0; k < 8; ++k) {
      double t;
      n += line_hits_triangle(p + glm::dvec3(0.3, -0.2, 5.0), glm::normalize(glm::dvec3(-0.3, 0.2, -5.0)), c, rim[k],
                              rim[(k + 1) % 8], &t);
    }
    return n;
  };
  EXPECT_GE(count_hits(c), 1);
  for (int k = 0; k < 8; ++k) {
    for (double s : {0.1, 0.37, 0.5, 0.91}) EXPECT_GE(count_hits(s * rim[k]), 1) << k << " " << s;
  }
  double t;
  EXPECT_FALSE(line_hits_triangle({2, 2, 1}, {0, 0, -1}, c, rim[0], rim[1], &t));
  ASSERT_TRUE(line_hits_triangle({0.3, 0.2, 1}, {0, 0, -1}, c, rim[0], rim[1], &t));
  EXPECT_NEAR(t, 1.0, 1e-15);
}

void check_box(Projection proj) {
  const glm::dvec3 lo{-1.0, -0.7, -0.5}, hi{1.0, 0.7, 0.5};
  const TetMesh m = box_mesh({6, 5, 4}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  const double a = 0.3, unit = 0.8, tau = -std::log(1 - a) / unit;
  const double c[3] = {0.2, 0.5, 0.9};
  const RenderSettings rs = ref_settings(80, 64, proj, TransferFunction({{0, c[0], c[1], c[2]}}, {{0, a}}, unit));
  ReferenceStats st;
  const Image img = reference(m, rs, &st);
  double worst = 0;
  uint64_t covered = 0;
  for (uint32_t j = 0; j < rs.height; ++j)
    for (uint32_t i = 0; i < rs.width; ++i) {
      glm::dvec3 o, d;
      spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
      const double L = box_chord(o, d, lo, hi), alpha = 1 - std::exp(-tau * L);
      worst = std::max(worst, double(std::abs(img.at(i, j)[3] - alpha)));
      for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(img.at(i, j)[k] - c[k] * alpha)));
      covered += L > 0;
    }
  EXPECT_LE(worst, 1e-6);
  EXPECT_EQ(st.rays_hit, covered);
  EXPECT_EQ(st.lost_walks, 0u);
  EXPECT_GT(covered, rs.width * rs.height / 10);
}

TEST(Reference, ConstantDensityBoxOrthographic) { check_box(Projection::Orthographic); }
TEST(Reference, ConstantDensityBoxPerspective) { check_box(Projection::Perspective); }

TEST(Reference, LinearScalarMatchesQuadrature) {
  const glm::dvec3 lo{-1.0, -0.8, -0.6}, hi{1.0, 0.8, 0.6};
  auto field = [](const glm::dvec3& p) { return 0.5 + 0.22 * p.x + 0.15 * p.y - 0.2 * p.z; };
  const TetMesh m = box_mesh({5, 4, 3}, lo, hi, field);
  TransferFunction tf({{0.0, 0.1, 0.1, 0.9}, {0.35, 0.1, 0.9, 0.3}, {0.55, 0.9, 0.9, 0.1}, {1.0, 0.9, 0.1, 0.1}},
                      {{0.0, 0.0}, {0.3, 0.05}, {0.45, 0.9}, {0.55, 0.1}, {0.7, 0.6}, {1.0, 0.2}}, 0.5);
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    const RenderSettings rs = ref_settings(60, 45, proj, tf);
    ReferenceStats st;
    const Image img = reference(m, rs, &st);
    double worst = 0;
    for (uint32_t j = 0; j < rs.height; j += 2)
      for (uint32_t i = 0; i < rs.width; i += 2) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        double ref[4];
        test::march_box_ray(tf, field, o, d, lo, hi, ref);
        for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(img.at(i, j)[k] - ref[k]));
      }
    // 20,000 midpoint steps are themselves good to about 1e-7.
    EXPECT_LE(worst, 5e-7) << int(proj);
  }
}

TEST(Reference, NonConvexMeshesReEnter) {
  const double a = 0.4, unit = 1.0, tau = -std::log(1 - a) / unit;
  auto one = [](const glm::dvec3&) { return 1.0; };
  const glm::dvec3 alo{-1, -1, -2}, ahi{1, 1, -1}, blo{-1, -1, 1}, bhi{1, 1, 2};
  TetMesh two = box_mesh({3, 3, 2}, alo, ahi, one);
  test::append_mesh(two, box_mesh({3, 3, 2}, blo, bhi, one));
  const glm::dvec3 clo{-1.5, -1.5, -1.5}, chi{1.5, 1.5, 1.5}, ilo{-0.5, -0.5, -0.5}, ihi{0.5, 0.5, 0.5};
  const TetMesh cavity =
      box_mesh({3, 3, 3}, clo, chi, one, [](int i, int j, int k) { return !(i == 1 && j == 1 && k == 1); });
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    RenderSettings rs = ref_settings(72, 56, proj, TransferFunction({{0, 1, 1, 1}}, {{0, a}}, unit));
    rs.camera.eye = {1.3, 0.9, 7.0};
    rs.camera.target = {0, 0, 0};
    rs.camera.height = 4.5;
    ReferenceStats s2, sc;
    const Image img_two = reference(two, rs, &s2), img_cav = reference(cavity, rs, &sc);
    double worst_two = 0, worst_cav = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        const double L2 = box_chord(o, d, alo, ahi) + box_chord(o, d, blo, bhi);
        const double Lc = box_chord(o, d, clo, chi) - box_chord(o, d, ilo, ihi);
        worst_two = std::max(worst_two, std::abs(img_two.at(i, j)[3] - (1 - std::exp(-tau * L2))));
        worst_cav = std::max(worst_cav, std::abs(img_cav.at(i, j)[3] - (1 - std::exp(-tau * Lc))));
      }
    EXPECT_LE(worst_two, 1e-6) << int(proj);
    EXPECT_LE(worst_cav, 1e-6) << int(proj);
    EXPECT_GT(s2.entries, s2.rays_hit) << "rays through both boxes enter twice";
    EXPECT_EQ(s2.lost_walks + sc.lost_walks, 0u);
  }
}

TEST(Reference, EyeInsideMeshIntegratesFromTheEye) {
  const glm::dvec3 lo{-1.0, -0.8, -1.2}, hi{1.1, 0.9, 1.0};
  const TetMesh m = box_mesh({5, 4, 6}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  const double a = 0.35, unit = 1.0, tau = -std::log(1 - a) / unit;
  for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
    RenderSettings rs = ref_settings(64, 48, proj, TransferFunction({{0, 1, 1, 1}}, {{0, a}}, unit));
    rs.camera.eye = {0.13, -0.07, 0.21};
    rs.camera.target = {0.5, 0.2, -1.0};
    rs.camera.fov_y = 70;
    rs.camera.height = 1.3;
    ReferenceStats st;
    const Image img = reference(m, rs, &st);
    double worst = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        glm::dvec3 o, d;
        spec_ray(rs.camera, rs.width, rs.height, int(i), int(j), &o, &d);
        worst = std::max(worst, std::abs(img.at(i, j)[3] - (1 - std::exp(-tau * box_chord(o, d, lo, hi)))));
      }
    EXPECT_LE(worst, 1e-6) << int(proj);
    EXPECT_EQ(st.rays_hit, uint64_t(rs.width) * rs.height);
  }
}

// Cell data: the walk holds each tet's own value, so a ray through two
// regions of different values is two constant segments (closed form).
TEST(Reference, CellDataInTwoRegionsMatchClosedForm) {
  const test::TwoRegions two;
  const TetMesh m = two.mesh();
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    const RenderSettings rs = ref_settings(60, 48, proj, two.tf());
    ReferenceStats st;
    const Image img = reference(m, rs, &st);
    const double worst = two.worst(img, rs);
    EXPECT_LE(worst, 1e-6) << int(proj);
  }
}

// Clip planes: the reference cuts its walk to the kept interval of each ray
// (two-region closed form, cut by an oblique plane and a crop box).
TEST(Reference, ClipPlanesMatchClosedForm) {
  const test::TwoRegions two;
  const TetMesh m = two.mesh();
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    RenderSettings rs = ref_settings(60, 48, proj, two.tf());
    rs.clip.planes.push_back({glm::dvec3(0.6, 0.3, -0.5), -0.1});
    rs.clip.add_box({-0.83, -1, -0.41}, {1, 0.52, 1});
    ReferenceStats st;
    const Image img = reference(m, rs, &st);
    const double worst = two.worst(img, rs);
    EXPECT_LE(worst, 1e-6) << int(proj);
    EXPECT_GT(st.segments_clipped, 0u);
  }
}

}  // namespace
}  // namespace zs
