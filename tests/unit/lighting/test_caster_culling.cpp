// Shadow maps built from triangles (src/lighting/shadow_map.cpp): casters that
// shadow nothing are left out and change no lit count.
#include <gtest/gtest.h>

#include "lighting/shadow_map.h"
#include "support/test_surface_meshes.h"

namespace zs {
namespace {

// Caster culling (shadow_map.cpp): a ground under everything shadows nothing,
// so it is left out of the map and every lit count stays the same; with a
// receiver below the ground it is kept and shadows that receiver.
TEST(Surfaces, CasterCullingLeavesOutOnlyWhatShadowsNothing) {
  TriangleMesh m = test::square_over_ground();
  Light light;
  light.direction = {0.3, -1, 0.2};
  const glm::dvec3 up(0, 1, 0);
  auto build = [&](bool cull, ShadowMapStats* st) {
    LightFit fit = start_fit(light);
    for (const glm::dvec3& p : m.points) fit.add(p);
    ShadowSettings s;
    s.map_size = 256;
    s.cull_casters = cull;
    return ShadowMap::build(m, light, fit, triangle_bounds(m), s, 2, st);
  };
  ShadowMapStats on, off;
  const ShadowMap a = build(true, &on), b = build(false, &off);
  EXPECT_EQ(on.casters_culled, 2u);  // the ground's two triangles
  EXPECT_EQ(off.casters_culled, 0u);
  EXPECT_EQ(on.casters, 2u);
  EXPECT_LT(on.texels_covered, off.texels_covered);
  uint32_t shadowed = 0;
  for (double x = -2.9; x < 2.9; x += 0.05)
    for (double z = -2.9; z < 2.9; z += 0.05) {
      const glm::dvec3 g(x, 0, z), o(0.45 * x / 2.9, 1, 0.45 * z / 2.9);
      ASSERT_EQ(a.lit_count(g, up), b.lit_count(g, up)) << x << "," << z;
      ASSERT_EQ(a.lit_count(o, up), b.lit_count(o, up)) << x << "," << z;
      shadowed += a.lit_count(g, up) == 0;
    }
  EXPECT_GT(shadowed, 100u);
  // A receiver below the ground: the ground must stay a caster.
  m.points.push_back({0, -1, 0});
  m.points.push_back({0.1, -1, 0});
  m.points.push_back({0, -1, 0.1});
  m.tris.push_back({8, 10, 9});
  m.surface.push_back(0);
  ShadowMapStats below;
  const ShadowMap c = build(true, &below);
  EXPECT_EQ(below.casters_culled, 1u);  // only the lowest triangle: everything is on its light side
  EXPECT_EQ(below.casters, 4u);
  EXPECT_EQ(c.lit_count({2.5, -1, 2.5}, up), 0u);  // under the ground, off the occluder's shadow
}

}  // namespace
}  // namespace zs
