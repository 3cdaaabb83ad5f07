// In app/: the budget checks of all three renderers, reached through SceneJob.
// Memory estimates count each tile clipped to the image: a 4096-pixel tile
// of a 512x512 image holds 512x512 pixels, and every per-tile buffer is
// sized by its tile's rect (issue 38, item 11).
#include <stdexcept>

#include <gtest/gtest.h>

#include "app/scene_job.h"
#include "geometry/tets/topology.h"
#include "support/test_meshes.h"
#include "render/volume/render_plan.h"

namespace zs {
namespace {

TEST(MemoryEstimate, LargestTileIsClippedToTheImage) {
  EXPECT_EQ((TileGrid{512, 512, 4096}.max_tile_pixels()), 512u * 512u);
  EXPECT_EQ((TileGrid{1000, 300, 64}.max_tile_pixels()), 64u * 64u);
  EXPECT_EQ((TileGrid{100, 30, 64}.max_tile_pixels()), 64u * 30u);
  EXPECT_EQ((TileGrid{1, 1, 4096}.max_tile_pixels()), 1u);
}

TEST(MemoryEstimate, PlanChargesTilePixelsNotTileSizeSquared) {
  const uint64_t budget = 200ull << 20;
  // 4 threads of a 512² tile fit 200 MiB; of a 4096² tile (7 GiB) they would not.
  const RenderPlan p = plan_render(budget, 1 << 20, TileGrid{512, 512, 4096}.max_tile_pixels(), 4);
  EXPECT_GT(p.max_fragments, 0u);
  EXPECT_EQ(p.max_fragments, plan_render(budget, 1 << 20, 512ull * 512, 4).max_fragments);
}

// The CLI form `render --width 512 --height 512 --tile-size 4096
// --memory-budget 200`: refused before as needing 3.8 GiB.
TEST(MemoryEstimate, VolumeBudgetIgnoresTileAreaOutsideTheImage) {
  const TetMesh m = test::box_mesh({4, 4, 4}, glm::dvec3(0.0), glm::dvec3(1.0), [](const glm::dvec3& p) { return p.x; });
  const Topology topo = build_topology(m);
  RenderSettings rs;
  rs.width = rs.height = 512;
  rs.threads = 2;
  rs.memory_budget_bytes = 200ull << 20;
  rs.tile_size = 4096;
  uint64_t big = 0, exact = 0;
  EXPECT_NO_THROW(big = check_memory_budget(m, topo, rs, 0));
  rs.tile_size = 512;  // one tile covering the image exactly: the same memory
  EXPECT_NO_THROW(exact = check_memory_budget(m, topo, rs, 0));
  EXPECT_EQ(big, exact);
  // A budget that cannot hold two 512² tiles is still refused.
  rs.tile_size = 4096;
  rs.memory_budget_bytes = 30ull << 20;
  EXPECT_THROW(check_memory_budget(m, topo, rs, 0), std::runtime_error);
}

// The sphere and surface renderers' budgets count the same way.
TEST(MemoryEstimate, SphereAndSurfaceBudgetsIgnoreTileAreaOutsideTheImage) {
  for (const char* json : {R"({"spheres": "spheres/small.sph"})", R"({"surfaces": [{"path": "surfaces/cube.off"}]})"}) {
    SceneInput in = load_scene_input_text(json, "s.json", ZS_TEST_DATA, {});
    RenderSettings& rs = in.scene.settings;
    rs.width = rs.height = 512;
    rs.threads = 2;
    rs.tile_size = 4096;
    rs.memory_budget_bytes = 100ull << 20;  // 4096² tiles would need gigabytes
    finish_scene(in);
    auto job = make_scene_job(in, false);
    EXPECT_NO_THROW(job->check_budget(0)) << json;
    EXPECT_NO_THROW(job->renderer(0, false)) << json;
  }
}

}  // namespace
}  // namespace zs
