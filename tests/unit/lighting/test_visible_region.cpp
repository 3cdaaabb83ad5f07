// visible_region_points: every corner of every triangle's polygon clipped to
// the view's frustum, against a plain clipper (Sutherland–Hodgman over the
// five planes, no shortcuts), on triangles inside, outside and across it.
#include <algorithm>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lighting/visible_region.h"

namespace zs {
namespace {

std::vector<glm::dvec3> reference(const TriangleMesh& m, const View& v, double z_near) {
  std::vector<glm::dvec3> out;
  const glm::dvec3 e = v.eye(), f = v.forward(), r = v.right(), u = v.up();
  const double hx = 0.5 * v.width() / v.scale_x(), hy = 0.5 * v.height() / v.scale_y();
  // Inside: z >= z_near, |x| <= hx·z, |y| <= hy·z (perspective).
  auto dist = [&](int pl, const glm::dvec3& c) {
    switch (pl) {
      case 0: return c.z - z_near;
      case 1: return hx * c.z - c.x;
      case 2: return hx * c.z + c.x;
      case 3: return hy * c.z - c.y;
      default: return hy * c.z + c.y;
    }
  };
  for (size_t t = 0; t < m.num_tris(); ++t) {
    std::vector<glm::dvec3> poly;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 d = m.points[m.tris[t][k]] - e;
      poly.push_back({glm::dot(d, r), glm::dot(d, u), glm::dot(d, f)});
    }
    for (int pl = 0; pl < 5 && !poly.empty(); ++pl) {
      std::vector<glm::dvec3> next;
      for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec3 &p = poly[k], &q = poly[(k + 1) % poly.size()];
        const double dp = dist(pl, p), dq = dist(pl, q);
        if (dp >= 0) next.push_back(p);
        if ((dp >= 0) != (dq >= 0)) next.push_back(p + (q - p) * (dp / (dp - dq)));
      }
      poly = next;
    }
    for (const glm::dvec3& c : poly) out.push_back(e + c.x * r + c.y * u + c.z * f);
  }
  return out;
}

TEST(VisibleRegion, ClippedCornersMatchAPlainClipper) {
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {0.5, 2.0, 6.0}, cam.target = {0, 0, 0}, cam.fov_y = 40;
  const View v(cam, 64, 48);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-4, 4), S(0.05, 1.5);
  TriangleMesh m;
  for (int t = 0; t < 400; ++t) {
    const glm::dvec3 c(U(rng), U(rng), U(rng));
    const double s = S(rng);
    for (int k = 0; k < 3; ++k) m.points.push_back(c + s * glm::dvec3(U(rng), U(rng), U(rng)) / 4.0);
    m.tris.push_back({uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2)});
  }
  const double z_near = 0.5;
  std::vector<glm::dvec3> got;
  visible_region_points(m, v, z_near, false, [&](const glm::dvec3& p) { got.push_back(p); });
  const std::vector<glm::dvec3> want = reference(m, v, z_near);
  ASSERT_EQ(got.size(), want.size());
  size_t inside = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(glm::length(got[i] - want[i]), 0.0, 1e-12) << i;
    inside += std::find(m.points.begin(), m.points.end(), got[i]) != m.points.end();
  }
  // All three kinds occur: whole triangles kept, clipped ones, dropped ones.
  EXPECT_GT(inside, 100u);
  EXPECT_LT(inside, got.size());
  EXPECT_LT(got.size(), 3 * 400u);
}

}  // namespace
}  // namespace zs
