// The AO direction sets (lighting/ao_directions.h): counts 2 + 4^(s+1),
// nesting, exact opposite pairs, unit length and an even spread.
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lighting/ao_directions.h"

namespace zs {
namespace {

TEST(AoDirections, CountsNestingPairsAndSpread) {
  EXPECT_TRUE(valid_direction_count(6));
  EXPECT_TRUE(valid_direction_count(258));
  EXPECT_TRUE(valid_direction_count(1026));
  for (uint64_t bad : {0, 1, 5, 7, 8, 17, 64, 257}) EXPECT_FALSE(valid_direction_count(bad)) << bad;
  std::vector<glm::dvec3> coarser;
  for (uint32_t n : {6u, 18u, 66u, 258u, 1026u}) {
    const std::vector<glm::dvec3> d = ao_directions(n);
    ASSERT_EQ(d.size(), n);
    // Every coarser set is a prefix, bit for bit.
    for (size_t i = 0; i < coarser.size(); ++i) ASSERT_EQ(d[i], coarser[i]) << n << " " << i;
    double min_dot_gap = 2, worst_cover = 1;
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < n; ++i) {
      EXPECT_NEAR(glm::length(d[i]), 1.0, 1e-15);
      if (i % 2 == 1) ASSERT_EQ(d[i], -d[i - 1]) << n << " " << i;  // exact opposite pairs
      sum += d[i];
      double nearest = -2;
      for (size_t j = 0; j < n; ++j)
        if (j != i) nearest = std::max(nearest, glm::dot(d[i], d[j]));
      min_dot_gap = std::min(min_dot_gap, 1 - nearest);  // no two directions coincide
    }
    EXPECT_LT(glm::length(sum), 1e-12);
    EXPECT_GT(min_dot_gap, 1e-4);
    // Coverage: every direction of a fine probe set lies within the angle of
    // a cap that shrinks like 1/sqrt(n) of some direction.
    const std::vector<glm::dvec3> probe = ao_directions(4098);
    for (const glm::dvec3& p : probe) {
      double best = -2;
      for (const glm::dvec3& q : d) best = std::max(best, glm::dot(p, q));
      worst_cover = std::min(worst_cover, best);
    }
    const double cap = std::acos(std::min(1.0, worst_cover));  // radians to the nearest direction
    EXPECT_LT(cap, 3.2 / std::sqrt(double(n))) << n;
    coarser = d;
  }
  // The octahedron's vertices first.
  const std::vector<glm::dvec3> six = ao_directions(6);
  EXPECT_EQ(six[0], glm::dvec3(1, 0, 0));
  EXPECT_EQ(six[5], glm::dvec3(0, 0, -1));
  try {
    ao_directions(64);
    FAIL() << "64 directions accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("6, 18, 66, 258"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace zs
