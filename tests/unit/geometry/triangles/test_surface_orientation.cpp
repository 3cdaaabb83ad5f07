// In geometry/triangles/: beside turn_solids_outward and auto_ground_height; SceneJob only renders.
// Surfaces whatever their winding, over a ground that never fights them:
// closed solids wound inward are turned outward (turn_solids_outward) and
// render as their outward twins bit for bit; open surfaces are drawn from
// both sides; the automatic ground goes a clear gap under a mesh lying flat
// (auto_ground_height) and stays at the lowest y under anything else.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "app/scene_job.h"
#include "geometry/triangles/closed_solids.h"
#include "geometry/triangles/ground_height.h"
#include "lighting/triangle_projection.h"

namespace zs {
namespace {

// The box [0, 1]×[0, h]×[0, 1], counter-clockwise from outside; `open_top`
// leaves out its top (y = h) square, `inward` reverses every triangle.
TriangleMesh box(double h, bool open_top, bool inward) {
  TriangleMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, h, 0}, {0, h, 0}, {0, 0, 1}, {1, 0, 1}, {1, h, 1}, {0, h, 1}};
  const std::vector<std::array<uint32_t, 4>> quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                      {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  for (const auto& q : quads) {
    if (open_top && q[0] == 2) continue;  // {2, 3, 7, 6}: the top
    m.tris.push_back({q[0], q[1], q[2]});
    m.tris.push_back({q[0], q[2], q[3]});
  }
  if (inward)
    for (auto& t : m.tris) std::swap(t[1], t[2]);
  m.surface.assign(m.tris.size(), 0);
  return m;
}

// An open n×n grid of squares over [0, 1]² in x and z at height y, facing +y
// (or −y when `down`).
TriangleMesh flat(int n, double y, bool down) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.push_back({double(i) / n, y, double(j) / n});
  auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.tris.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});  // counter-clockwise from +y
      m.tris.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  if (down)
    for (auto& t : m.tris) std::swap(t[1], t[2]);
  m.surface.assign(m.tris.size(), 0);
  return m;
}

struct Frame {
  std::vector<float> px;  // R, G, B, A, Z, lit0 per pixel
  nlohmann::json stats;
  std::string summary;
};

struct BufferSink : TileSink {
  TileGrid g;
  std::vector<float> px;
  explicit BufferSink(const TileGrid& grid) : g(grid), px(size_t(grid.width) * grid.height * grid.channels) {}
  void tile(const TileRect& r, const float* p) override {
    const size_t c = g.channels, w = r.x1 - r.x0;
    for (uint32_t y = r.y0; y < r.y1; ++y)
      std::copy_n(p + (y - r.y0) * w * c, w * c, &px[(size_t(y) * g.width + r.x0) * c]);
  }
};

// `mesh` as the one surface of a scene (`ground`: its JSON value, or none).
Frame render(const TriangleMesh& mesh, const std::string& ground) {
  SceneData data;
  data.surfaces["/mem/m.obj"] = mesh;
  const std::string json = R"({"surfaces": ["/mem/m.obj"], "image": {"width": 96, "height": 72})" +
                           (ground.empty() ? std::string() : R"(, "ground": )" + ground) + "}";
  SceneInput in = load_scene_input_text(json, "s.json", "", data);
  in.scene.settings.threads = 2;
  finish_scene(in, Projection::Perspective);
  auto job = make_scene_job(in, false);
  EXPECT_EQ(job->grid().channels, 6u);
  BufferSink sink(job->grid());
  std::vector<double> ms;
  auto r = render_frames(*job, 1, sink, 0, false, &ms);
  return {sink.px, job->stats(*r, FrameReport{}), job->summary(*r, 1.0)};
}

TEST(SurfaceOrientation, InwardSolidsAreTurnedOutwardOnly) {
  const TriangleMesh out = box(1, false, false);
  TriangleMesh m = box(1, false, true);
  SolidCounts c = turn_solids_outward(m);
  EXPECT_EQ(c.components, 1u);
  EXPECT_EQ(c.closed, 1u);
  EXPECT_EQ(c.inward, 1u);
  EXPECT_EQ(m.tris, out.tris);  // exactly the outward twin
  EXPECT_EQ(m.solid, std::vector<int8_t>(12, 1));
  // Outward solids and open surfaces (either winding) are left as they are.
  for (TriangleMesh keep : {out, box(1, true, true), box(1, true, false), flat(3, 0, true)}) {
    const auto tris = keep.tris;
    c = turn_solids_outward(keep);
    EXPECT_EQ(c.inward, 0u);
    EXPECT_EQ(keep.tris, tris);
  }
}

TEST(SurfaceOrientation, InwardCubeRendersAsTheOutwardOne) {
  const Frame a = render(box(1, false, false), "true"), b = render(box(1, false, true), "true");
  ASSERT_EQ(a.px.size(), b.px.size());
  size_t differ = 0, covered = 0;
  for (size_t i = 0; i < a.px.size(); ++i) differ += std::memcmp(&a.px[i], &b.px[i], sizeof(float)) != 0;
  for (size_t p = 0; p < a.px.size() / 6; ++p) covered += a.px[p * 6 + 3] > 0;
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(covered, 1000u);
  EXPECT_EQ(a.stats["orientation"]["turned_outward"], 0);
  EXPECT_EQ(b.stats["orientation"]["turned_outward"], 1);
  EXPECT_EQ(b.stats["orientation"]["closed_solids"], 1);
  EXPECT_EQ(b.stats["triangles"]["back_face_culled"], a.stats["triangles"]["back_face_culled"]);
  EXPECT_EQ(a.summary.find("turned outward"), std::string::npos) << a.summary;
  EXPECT_NE(b.summary.find(", 1 closed surface wound inward turned outward"), std::string::npos) << b.summary;
}

// An open box seen from above shows its inside through the top whichever
// way it is wound; back-face culling would hide the far walls' inner sides
// (or, wound inward, every outer side).
TEST(SurfaceOrientation, OpenSurfacesShowBothSides) {
  const Frame a = render(box(1, true, false), ""), b = render(box(1, true, true), "");
  ASSERT_EQ(a.px.size(), b.px.size());
  size_t covered = 0, differ = 0;
  double worst = 0;
  for (size_t p = 0; p < a.px.size() / 6; ++p) {
    const float* x = &a.px[p * 6];
    const float* y = &b.px[p * 6];
    covered += x[3] > 0;
    differ += x[3] != y[3] || x[4] != y[4];  // alpha, Z: the same surface in front
    for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(x[k] - y[k])));
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_LT(worst, 1e-4);  // Phong normals interpolated from the other corner order
  EXPECT_GT(covered, 1000u);
  EXPECT_EQ(a.stats["orientation"]["closed_solids"], 0);
  EXPECT_EQ(a.stats["orientation"]["two_sided_triangles"], 10);
  EXPECT_EQ(a.stats["triangles"]["back_face_culled"], 0);
  EXPECT_GT(a.stats["triangles"]["back_faces_two_sided"].get<int>(), 0);
  // The inner side of the far walls is in view: every covered pixel is
  // covered whichever winding, and more than the outer sides alone cover.
  TriangleMesh outer = box(1, true, false);
  outer.two_sided.clear();  // one-sided: as before
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {0.5 + 1.2, 2.5, 0.5 + 2.0};
  cam.target = {0.5, 0.5, 0.5};
  ProjectedTriangles pt;
  ProjectCounts one, two;
  project_triangles(outer, View(cam, 64, 64), {true, true, 1e-6}, &pt, &one);
  outer.two_sided.assign(outer.num_tris(), 1);
  project_triangles(outer, View(cam, 64, 64), {true, true, 1e-6}, &pt, &two);
  EXPECT_GT(one.back_culled, 0u);
  EXPECT_EQ(two.back_culled, 0u);
  EXPECT_EQ(two.back_two_sided, one.back_culled);
  EXPECT_EQ(pt.corners.size(), size_t(two.triangles - two.view_culled));
}

TEST(GroundPlacement, FlatOrThinMeshesGetAGapOthersTouch) {
  // A closed box stands on its bottom: the ground touches it, as before.
  TriangleMesh m = box(0.5, false, false);
  turn_solids_outward(m);
  GroundPlacement g = auto_ground_height(m);
  EXPECT_FALSE(g.lowered);
  EXPECT_EQ(g.height, 0.0);
  // Flat at y = 2 (either way up), a thin closed slab, an open box's floor:
  // 1 % of the largest extent lower.
  for (TriangleMesh f : {flat(4, 2, false), flat(4, 2, true), box(1e-4, false, false), box(1, true, false)}) {
    const double lo = f.points[0].y;
    turn_solids_outward(f);
    g = auto_ground_height(f);
    EXPECT_TRUE(g.lowered);
    EXPECT_DOUBLE_EQ(g.gap, 0.01);
    EXPECT_DOUBLE_EQ(g.height, lo - 0.01);
  }
  // Every point the same: no extent, the ground at the point (nothing to fight).
  TriangleMesh dot = flat(1, 3, false);
  for (auto& p : dot.points) p = {1, 3, 1};
  g = auto_ground_height(dot);
  EXPECT_FALSE(g.lowered);
  EXPECT_EQ(g.height, 3.0);
}

// A flat mesh over the automatic ground: every pixel it covers alone is its
// own (same depth, same colour) with the ground there too, so the ground is
// strictly behind it everywhere; where it is not, the ground is.
TEST(GroundPlacement, FlatMeshHidesTheGroundUnderItEverywhere) {
  for (bool down : {false, true}) {
    const TriangleMesh m = flat(16, 0.5, down);
    const Frame alone = render(m, ""), over = render(m, "true");
    size_t mesh_px = 0, wrong = 0, ground_px = 0;
    for (size_t p = 0; p < alone.px.size() / 6; ++p) {
      const float* a = &alone.px[p * 6];
      const float* b = &over.px[p * 6];
      if (a[3] > 0) {
        ++mesh_px;
        wrong += a[4] != b[4] || a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
      } else {
        ground_px += b[3] > 0 && b[4] < std::numeric_limits<float>::infinity();
      }
    }
    EXPECT_GT(mesh_px, 500u) << down;
    EXPECT_EQ(wrong, 0u) << down;
    EXPECT_GT(ground_px, 1000u) << down;
    EXPECT_LT(over.stats["ground"]["height"].get<double>(), 0.5 - 0.009) << down;
    EXPECT_NE(over.summary.find("ground lowered"), std::string::npos) << over.summary;
  }
}

}  // namespace
}  // namespace zs
