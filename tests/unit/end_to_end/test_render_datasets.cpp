// In end_to_end/: it runs mesh readers, scene, the ZSweep engine and the reference together.
// The real meshes render with the automatic camera and transfer function:
// finite values everywhere, a sensible number of covered pixels, and the
// ZSweep image within float rounding of the reference ray caster.
#include <cmath>

#include <glm/vec3.hpp>

#include <gtest/gtest.h>

#include "geometry/tets/io/mesh_io.h"
#include "output/image_compare.h"
#include "geometry/tets/topology.h"
#include "render/reference/reference_renderer.h"
#include "scene/scene.h"
#include "support/test_paths.h"
#include "render/volume/zsweep_renderer.h"
#include "app/reference_scene.h"
#include "app/scene_job.h"
#include "raster/image_sink.h"

namespace zs {
namespace {

// camera: the automatic one for `proj` unless given; clip: the scene's
// clip planes (tets and segments clipped must then be counted).
void render_finite(const TetMesh& m, Projection proj, uint64_t min_rendered, const ClipRegion& clip = {},
                   const Camera* camera = nullptr) {
  RenderSettings rs;
  rs.width = 160;
  rs.height = 120;
  rs.camera = camera ? *camera : auto_camera(m, proj, rs.width, rs.height);
  rs.tf = default_transfer_function(m);
  rs.threads = 2;
  rs.clip = clip;
  RenderStats st;
  const Topology topo = build_topology(m);
  const Image img = render_zsweep(m, topo, rs, &st);
  size_t bad = 0;
  for (float v : img.rgba) bad += !std::isfinite(v) || v < -1e-6f || v > 1 + 1e-5f;
  EXPECT_EQ(bad, 0u);
  EXPECT_GE(st.rendered_pixels, min_rendered);
  EXPECT_EQ(st.faces_clipped, 0u);
  EXPECT_EQ(st.cell_data_tets > 0, m.has_cell_scalars());
  if (!clip.empty()) {
    EXPECT_GT(st.tets_clipped, 0u);
    EXPECT_GT(st.segments_clipped, 0u);
  }
  ReferenceStats rst;
  const Image ref = render_reference(m, topo, rs, rs.tf, &rst);
  const ImageDiff d = compare_images(img, ref);
  EXPECT_LE(d.max_abs, 1e-5) << "worst pixel " << d.worst_x << ", " << d.worst_y;
  EXPECT_EQ(rst.lost_walks, 0u);
}

TEST(RenderDatasets, Spx) {
  ZS_REQUIRE_SHARED(p, "spx.off");
  const TetMesh m = read_mesh(p);
  // spx fills about a tenth of the automatic frame (its bounding sphere).
  render_finite(m, Projection::Orthographic, 1000);
  render_finite(m, Projection::Perspective, 1000);
}

TEST(RenderDatasets, BluntFinDensity) {
  ZS_REQUIRE_SHARED(xyz, "bluntfinxyz.bin");
  ZS_REQUIRE_SHARED(q, "bluntfinq.bin");
  const TetMesh m = read_mesh(xyz, {"density", q});
  render_finite(m, Projection::Perspective, 3000);
}

TEST(RenderDatasets, PostVelocityMagnitude) {
  ZS_REQUIRE_SHARED(xyz, "postxyz.bin");
  ZS_REQUIRE_SHARED(q, "postq.bin");
  const TetMesh m = read_mesh(xyz, {"velocity-magnitude", q});
  render_finite(m, Projection::Orthographic, 3000);
}

// An oblique plane through the fin and a crop box: what the planes keep,
// with the plane's cut faces dark, as the reference cuts it.
TEST(RenderDatasets, BluntFinClipped) {
  ZS_REQUIRE_SHARED(xyz, "bluntfinxyz.bin");
  ZS_REQUIRE_SHARED(q, "bluntfinq.bin");
  const TetMesh m = read_mesh(xyz, {"density", q});
  ClipRegion clip;
  clip.planes.push_back({glm::dvec3(0.4, -1.0, 0.3), 2.5});
  clip.add_box({-5, -1, -1}, {10, 9, 4.5});
  render_finite(m, Projection::Perspective, 1000, clip);
  render_finite(m, Projection::Orthographic, 1000, clip);
}

// kiefer's stress per cell, each tet at its cell's value, from an eye in no
// face's plane (a ray in a face between cells may take either value).
TEST(RenderDatasets, KieferCellData) {
  ZS_REQUIRE_SHARED(p, "kiefer.vtu");
  const TetMesh m = read_mesh(p);
  ASSERT_TRUE(m.has_cell_scalars());
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {6.1, -8.3, 5.9};
  cam.target = {0.05, 0.02, 1.6};
  cam.up = {0, 0, 1};
  cam.fov_y = 30;
  render_finite(m, Projection::Perspective, 3000, {}, &cam);
  ClipRegion clip;
  clip.planes.push_back({glm::dvec3(1.0, 0.2, 0.1), -0.3});
  render_finite(m, Projection::Perspective, 2000, clip, &cam);
}

// The blunt fin with a clip plane and its density's isosurface inside the
// volume (the docs' example, smaller): the engine over the surface renderer's
// tiles and the reference's walk over the same surfaces agree.
TEST(RenderDatasets, BluntFinWithIsosurfaceInside) {
  ZS_REQUIRE_SHARED(xyz, "bluntfinxyz.bin");
  ZS_REQUIRE_SHARED(q, "bluntfinq.bin");
  const std::string json = R"({"mesh": {"path": ")" + xyz + R"(", "q": ")" + q + R"("},
    "surfaces": [{"isosurface": [1.9]}], "shadows": {"mode": "exact"},
    "clip": [{"plane": [0, -1, 0, 1.5]}], "image": {"width": 160, "height": 100},
    "camera": {"projection": "perspective", "eye": [-10, 14, 26], "target": [3, 3, 2.5], "up": [0, 1, 0], "fov_y": 35}})";
  SceneInput in = load_scene_input_text(json, "bluntfin.json", "", {});
  in.scene.settings.threads = 2;
  finish_scene(in);
  auto job = make_scene_job(in, false);
  ImageSink sink(job->grid());
  auto r = job->renderer(0, false);
  r->render_tiles(sink, nullptr);
  const nlohmann::json st = job->stats(*r, FrameReport{});
  EXPECT_GT(st["rays_stopped_by_geometry"].get<uint64_t>(), 300u);
  EXPECT_GT(st["tets_clipped"].get<uint64_t>(), 0u);
  const ReferenceImage ref = reference_image(in, 0);
  double worst = 0;
  for (size_t p = 0; p < sink.image.rgba.size(); ++p)
    worst = std::max(worst, double(std::abs(sink.image.rgba[p] - ref.pixels[p])));
  EXPECT_LE(worst, 1e-5);
}

}  // namespace
}  // namespace zs
