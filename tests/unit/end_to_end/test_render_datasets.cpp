// In end_to_end/: it runs mesh readers, scene, the ZSweep engine and the reference together.
// The real meshes render with the automatic camera and transfer function:
// finite values everywhere, a sensible number of covered pixels, and the
// ZSweep image within float rounding of the reference ray caster.
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/tets/io/mesh_io.h"
#include "output/image_compare.h"
#include "geometry/tets/topology.h"
#include "render/reference/reference_renderer.h"
#include "scene/scene.h"
#include "support/test_paths.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {
namespace {

void render_finite(const TetMesh& m, Projection proj, uint64_t min_rendered) {
  RenderSettings rs;
  rs.width = 160;
  rs.height = 120;
  rs.camera = auto_camera(m, proj, rs.width, rs.height);
  rs.tf = default_transfer_function(m);
  rs.threads = 2;
  RenderStats st;
  const Topology topo = build_topology(m);
  const Image img = render_zsweep(m, topo, rs, &st);
  size_t bad = 0;
  for (float v : img.rgba) bad += !std::isfinite(v) || v < -1e-6f || v > 1 + 1e-5f;
  EXPECT_EQ(bad, 0u);
  EXPECT_GE(st.rendered_pixels, min_rendered);
  EXPECT_EQ(st.faces_clipped, 0u);
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

}  // namespace
}  // namespace zs
