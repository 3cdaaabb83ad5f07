// SceneJob (src/app/scene_job.h): the one path from a loaded scene to its
// renderer, channels and stats that the CLI and the Python module share.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "app/reference_scene.h"
#include "app/scene_job.h"
#include "support/test_paths.h"

namespace zs {
namespace {

// Tiles into one (width × height × channels) buffer, counting them.
struct BufferSink : TileSink {
  TileGrid g;
  std::vector<float> px;
  uint32_t tiles = 0;
  explicit BufferSink(const TileGrid& grid) : g(grid), px(size_t(grid.width) * grid.height * grid.channels, -1.f) {}
  void tile(const TileRect& r, const float* p) override {
    ++tiles;
    const size_t c = g.channels, w = r.x1 - r.x0;
    for (uint32_t y = r.y0; y < r.y1; ++y)
      std::copy_n(p + (y - r.y0) * w * c, w * c, &px[(size_t(y) * g.width + r.x0) * c]);
  }
};

SceneInput scene(const std::string& json, const SceneData& data = {}) {
  SceneInput in = load_scene_input_text(json, "s.json", ZS_TEST_DATA, data);
  in.scene.settings.threads = 2;
  finish_scene(in);
  return in;
}

TEST(SceneJob, SphereSceneChannelsFramesAndStats) {
  SceneInput in = scene(R"({"spheres": "spheres/small.sph", "image": {"width": 40, "height": 30},
                            "ao": {"directions": 6, "map_size": 64}})");
  auto job = make_scene_job(in, false);
  EXPECT_EQ(job->grid().channels, 6u);
  EXPECT_EQ(job->channel_names(), (std::vector<std::string>{"R", "G", "B", "A", "Z", "AO"}));
  BufferSink sink(job->grid());
  std::vector<double> frame_ms;
  auto r = render_frames(*job, 3, sink, 0, false, &frame_ms);
  EXPECT_EQ(frame_ms.size(), 3u);
  EXPECT_EQ(sink.tiles, job->grid().count());  // only the last frame reaches the sink
  FrameReport f;
  f.frame_ms = frame_ms;
  f.best_ms = 0.25;
  const nlohmann::json st = job->stats(*r, f);
  EXPECT_EQ(st["renderer"], "spheres");
  EXPECT_EQ(st["time_ms"]["total"].get<double>(), 0.25);
  EXPECT_EQ(st["frame_ms"].size(), 3u);
  EXPECT_EQ(st["ao"]["directions"], 6);
  // The stats count what the sink got: every covered pixel has alpha > 0 and a finite Z.
  uint64_t covered = 0;
  for (size_t p = 0; p < sink.px.size() / 6; ++p) {
    const float* q = &sink.px[p * 6];
    const bool hit = q[3] > 0;
    covered += hit;
    EXPECT_EQ(hit, std::isfinite(q[4])) << p;
    if (hit) EXPECT_TRUE(q[5] >= 0 && q[5] <= 1) << p;
  }
  EXPECT_EQ(st["rendered_pixels"].get<uint64_t>(), covered);
  EXPECT_GT(covered, 0u);
  EXPECT_EQ(job->empty_reason(*r), "");
  EXPECT_NE(job->summary(*r, 1.5).find("1.5 ms"), std::string::npos);
}

TEST(SceneJob, VolumeFromDataAndMpiTotals) {
  // A single tet given as data (the Python module's way), not a file.
  SceneData data;
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.scalars = {0, 1, 2, 3};
  m.tets = {{0, 1, 2, 3}};
  data.meshes["/<data>/m"] = m;
  SceneInput in = scene(R"({"mesh": "/<data>/m", "image": {"width": 24, "height": 24}})", data);
  auto job = make_scene_job(in, false);
  EXPECT_EQ(job->grid().channels, 4u);
  EXPECT_TRUE(job->channel_names().empty());
  BufferSink sink(job->grid());
  std::vector<double> frame_ms;
  auto r = render_frames(*job, 1, sink, 0, false, &frame_ms);
  FrameReport f;
  f.mpi_wall_ms = 100;  // MPI: the setup plus the ranks' wall time
  const nlohmann::json st = job->stats(*r, f);
  EXPECT_DOUBLE_EQ(st["time_ms"]["total"].get<double>(), st["time_ms"]["setup"].get<double>() + 100);
  EXPECT_EQ(st["mesh"]["tets"], 1);
  EXPECT_GT(st["rendered_pixels"].get<uint64_t>(), 0u);
  // The reference of the same scene, in memory: RGBA, close to the render.
  const ReferenceImage ref = reference_image(in, 0);
  ASSERT_EQ(ref.names.size(), 4u);
  double worst = 0;
  for (size_t k = 0; k < ref.pixels.size(); ++k) worst = std::max(worst, std::abs(double(ref.pixels[k] - sink.px[k])));
  EXPECT_LT(worst, 1e-5);
}

TEST(SceneJob, SurfaceSceneHasOneLitChannelPerLight) {
  SceneInput in = scene(R"({"surfaces": ["surfaces/pyramid.obj"], "ground": {"height": 0},
                            "lights": [{"type": "directional", "direction": [1, -2, 0.5]},
                                       {"type": "directional", "direction": [-1, -2, 0.5]}],
                            "image": {"width": 32, "height": 24}})");
  auto job = make_scene_job(in, true);  // no culling
  EXPECT_EQ(job->grid().channels, 7u);
  EXPECT_EQ(job->channel_names()[5], "lit0");
  EXPECT_EQ(job->channel_names()[6], "lit1");
  EXPECT_TRUE(job->overlap_frames());
  BufferSink sink(job->grid());
  std::vector<double> frame_ms;
  auto r = render_frames(*job, 2, sink, 0, false, &frame_ms);
  const nlohmann::json st = job->stats(*r, FrameReport{});
  EXPECT_EQ(st["lights"], 2);
  EXPECT_EQ(st["culling"]["back_face"], false);
  EXPECT_THROW(reference_image(in, 0), std::runtime_error);  // surfaces: the exact mode instead
}

}  // namespace
}  // namespace zs
