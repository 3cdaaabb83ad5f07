// The sphere test sets C1-C4 (src/geometry/spheres/generate/).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "geometry/spheres/generate/pore_balls.h"
#include "geometry/spheres/generate/portable_random.h"
#include "geometry/spheres/generate/test_sets.h"

namespace zs {
namespace {

bool same(const SphereSet& a, const SphereSet& b) {
  return a.centres == b.centres && a.radii == b.radii && a.rgba == b.rgba;
}

void expect_sane(const SphereSet& s, size_t n, double rmin, double rmax) {
  ASSERT_EQ(s.size(), n);
  ASSERT_EQ(s.radii.size(), n);
  ASSERT_EQ(s.rgba.size(), n);
  for (size_t i = 0; i < n; ++i) {
    ASSERT_TRUE(s.radii[i] >= rmin && s.radii[i] <= rmax) << i << " " << s.radii[i];
    for (int k = 0; k < 4; ++k) ASSERT_TRUE(s.rgba[i][k] >= 0.f && s.rgba[i][k] <= 1.f) << i;
    ASSERT_TRUE(std::isfinite(s.centres[i].x) && std::isfinite(s.centres[i].y) && std::isfinite(s.centres[i].z));
  }
}

double fraction(const SphereSet& s, float lo, float hi) {
  size_t k = 0;
  for (const glm::vec4& c : s.rgba) k += c.a >= lo && c.a <= hi;
  return double(k) / double(s.size());
}

TEST(SphereGenerators, PortableRandomIsTheStandardEngine) {
  // mt19937_64's 10000th output is fixed by the standard (seed 5489).
  PortableRandom r(5489);
  for (int i = 0; i < 9999; ++i) r.bits();
  EXPECT_EQ(r.bits(), 9981545732273789042ull);
  PortableRandom u(7);
  double lo = 1, hi = 0, sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const double x = u.uniform();
    lo = std::min(lo, x), hi = std::max(hi, x), sum += x;
    ASSERT_LT(u.below(10), 10u);
  }
  EXPECT_GE(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_NEAR(sum / 100000, 0.5, 0.01);
}

TEST(SphereGenerators, CountsDeterminismAndSeeds) {
  for (size_t n : {1u, 999u, 3001u}) {
    EXPECT_EQ(generate_c1(n, 3).size(), n);
    EXPECT_EQ(generate_c3(n, 3).size(), n);
    EXPECT_EQ(generate_c4(n, 3).size(), n);
  }
  EXPECT_TRUE(same(generate_c1(2000, 11), generate_c1(2000, 11)));
  EXPECT_TRUE(same(generate_c3(2000, 11), generate_c3(2000, 11)));
  EXPECT_TRUE(same(generate_c4(2000, 11), generate_c4(2000, 11)));
  EXPECT_FALSE(same(generate_c1(2000, 11), generate_c1(2000, 12)));
  EXPECT_FALSE(same(generate_c3(2000, 11), generate_c3(2000, 12)));
  EXPECT_FALSE(same(generate_c4(2000, 11), generate_c4(2000, 12)));
}

TEST(SphereGenerators, C1SparseCubeWithDenseCentreMostlyOpaque) {
  const SphereSet s = generate_c1(20000, 1);
  expect_sane(s, 20000, 0.1, 0.6);
  size_t centre = 0;
  for (const auto& c : s.centres) {
    ASSERT_LE(std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)}), 50.0);
    centre += glm::length(c) < 10.0;
  }
  // Uniform alone would put 0.2% within 10 of the centre; the cluster (30%
  // of the spheres, 74% of them within 2 sigma) ~22%.
  EXPECT_GT(centre, 20000u * 20 / 100);
  EXPECT_NEAR(fraction(s, 1.f, 1.f), 0.8, 0.02);
  EXPECT_NEAR(fraction(s, 0.2f, 0.6f), 0.2, 0.02);
}

TEST(SphereGenerators, C3ClustersAreSeparatedTranslucentAtTheBorder) {
  const size_t n = 27 * 2000;  // 27 clusters on a 3x3x3 grid
  const SphereSet s = generate_c3(n, 5);
  expect_sane(s, n, 0.08, 0.15);
  // Spheres k*2000 .. k*2000+1999 form cluster k: each lies within 2.65 of
  // its cluster's mean, and clusters' extents are apart.
  std::vector<glm::dvec3> mean(27, glm::dvec3(0));
  for (size_t i = 0; i < n; ++i) mean[i / 2000] += s.centres[i] / 2000.0;
  std::vector<double> extent(27, 0);
  for (size_t i = 0; i < n; ++i)
    extent[i / 2000] = std::max(extent[i / 2000], glm::length(s.centres[i] - mean[i / 2000]) + s.radii[i]);
  for (int a = 0; a < 27; ++a) {
    EXPECT_LT(extent[a], 2.8);
    for (int b = a + 1; b < 27; ++b) EXPECT_GT(glm::length(mean[a] - mean[b]) - extent[a] - extent[b], 2.0) << a << " " << b;
  }
  // The centre cluster (cell 1,1,1 = 13) is opaque, corner ones are partly translucent.
  for (size_t i = 13 * 2000; i < 14 * 2000; ++i) ASSERT_EQ(s.rgba[i].a, 1.f);
  size_t corner_translucent = 0;
  for (size_t i = 0; i < 2000; ++i) corner_translucent += s.rgba[i].a < 0.5f;
  EXPECT_GT(corner_translucent, 1000u);
}

TEST(SphereGenerators, C4IsOneBlockWithRedAndGreenTranslucentBlobs) {
  const SphereSet s = generate_c4(27000, 2);  // 30^3
  expect_sane(s, 27000, 0.5, 0.7);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const auto& c : s.centres) lo = glm::min(lo, c), hi = glm::max(hi, c);
  const glm::dvec3 size = hi - lo;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(size[k], 29.0, 0.5);  // a cube of 30 lattice sites, jitter 0.2
  size_t red = 0, green = 0;
  for (const auto& c : s.rgba) {
    if (c.r > 0.6f && c.g < 0.2f) {
      ++red;
      EXPECT_LE(c.a, 0.08f);
    }
    if (c.g > 0.6f && c.r < 0.2f) {
      ++green;
      EXPECT_LE(c.a, 0.08f);
    }
  }
  EXPECT_GT(red, 100u);
  EXPECT_GT(green, 100u);
  // Clustered: a red sphere's nearest red neighbours are close (blobs), far
  // closer than red spheres spread uniformly would be.
  double near_red = 0;
  size_t counted = 0;
  for (size_t i = 0; i < s.size() && counted < 50; ++i) {
    if (!(s.rgba[i].r > 0.6f && s.rgba[i].g < 0.2f)) continue;
    double best = 1e9;
    for (size_t j = 0; j < s.size(); ++j)
      if (j != i && s.rgba[j].r > 0.6f && s.rgba[j].g < 0.2f) best = std::min(best, glm::length(s.centres[i] - s.centres[j]));
    near_red += best, ++counted;
  }
  EXPECT_LT(near_red / double(counted), 1.6);  // lattice neighbours (pitch 1)
  EXPECT_GT(fraction(s, 0.1f, 0.3f), 0.5);     // translucent background
  EXPECT_GT(fraction(s, 1.f, 1.f), 0.02);      // and some opaque
}

TEST(SphereGenerators, C2MaximalBallsOfTheSkullImage) {
  const std::string tarball = "/usr/share/doc/libcgal-dev/data.tar.gz";
  if (!std::filesystem::exists(tarball)) GTEST_SKIP() << "no " << tarball << " (apt-get install libcgal-demo)";
  PoreBallsInfo info;
  const SphereSet s = generate_c2(3000, 1, tarball, &info);
  EXPECT_EQ(info.upsample, 1);  // 64^3 already has more than 3000 balls
  EXPECT_GT(info.maximal_balls, 3000u);
  expect_sane(s, 3000, 3.6, 1e9);  // radius >= 1 voxel (>= 3.65 world units)
  for (size_t i = 1; i < s.size(); ++i) ASSERT_GE(s.radii[i - 1], s.radii[i]);  // the largest first
  EXPECT_GT(fraction(s, 0.02f, 0.15f), 0.85);  // mostly highly translucent
  EXPECT_TRUE(same(s, generate_c2(3000, 1, tarball)));
  // Maximal: the largest ball does not contain the second largest.
  const double d = glm::length(s.centres[0] - s.centres[1]);
  EXPECT_GT(d + s.radii[1], s.radii[0]);
}

TEST(SphereGenerators, C2WithoutTheImageNamesThePackage) {
  try {
    generate_c2(10, 1, "/nonexistent/data.tar.gz");
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(),
                 "/nonexistent/data.tar.gz: not found: C2 needs the 3D images of Debian's libcgal-demo (apt-get install "
                 "libcgal-demo)");
  }
}

}  // namespace
}  // namespace zs
