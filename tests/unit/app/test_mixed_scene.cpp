// Volumes with geometry inside (app/mixed_job.cpp): a scene's opaque sphere
// drawn by the sphere renderer, flat-shaded, inside a constant-density box:
// each pixel is the volume's emission up to the sphere, then the sphere's
// colour times the transmittance to it (closed form), in both projections and
// from an eye inside the box; the reference agrees; the stats count the rays
// the geometry stopped.
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "app/reference_scene.h"
#include "app/scene_job.h"
#include "raster/image_sink.h"
#include "support/test_meshes.h"

namespace zs {
namespace {

TEST(MixedScene, OpaqueSphereInAConstantVolumeMatchesClosedForm) {
  const glm::dvec3 lo{-1.0, -0.7, -0.5}, hi{1.0, 0.7, 0.5};
  SceneData data;
  data.meshes["/data/box"] = test::box_mesh({6, 5, 4}, lo, hi, [](const glm::dvec3&) { return 1.0; });
  SphereSet s;
  const glm::dvec3 centre{0.15, -0.05, 0.02};
  const double radius = 0.33, sc[3] = {0.9, 0.6, 0.1};
  s.centres = {centre};
  s.radii = {radius};
  s.rgba = {glm::vec4(float(sc[0]), float(sc[1]), float(sc[2]), 1.f)};
  data.spheres["/data/ball"] = s;
  const double a = 0.35, unit = 0.7, tau = -std::log(1 - a) / unit, c[3] = {0.2, 0.5, 0.9};
  for (int inside = 0; inside < 2; ++inside)
    for (const char* proj : {"orthographic", "perspective"}) {
      const std::string eye = inside ? "[-0.8, 0.4, 0.35]" : "[2.5, 1.7, 4.0]";
      const std::string json = std::string(R"({"mesh": "/data/box", "spheres": {"path": "/data/ball", "color": "rgba"},
        "shading": {"model": "flat"}, "image": {"width": 64, "height": 48, "background": [0.05, 0.1, 0.15, 1]},
        "camera": {"projection": ")") + proj + R"(", "eye": )" + eye + R"(, "target": [0.15, -0.05, 0.02],
                   "up": [0, 1, 0], "height": 3.2, "fov_y": 75},
        "transfer_function": {"color": [[0, 0.2, 0.5, 0.9]], "opacity": [[0, 0.35]], "unit_distance": 0.7}})";
      SceneInput in = load_scene_input_text(json, "s.json", "", data);
      in.scene.settings.threads = 2;
      finish_scene(in);
      ASSERT_TRUE(in.scene.with_spheres);
      auto job = make_scene_job(in, false);
      ImageSink sink(job->grid());
      auto r = job->renderer(0, false);
      r->render_tiles(sink, nullptr);
      const Camera& cam = in.scene.settings.camera;
      const double* bg = in.scene.settings.background;
      double worst = 0;
      for (uint32_t j = 0; j < 48; ++j)
        for (uint32_t i = 0; i < 64; ++i) {
          glm::dvec3 o, d;
          test::spec_ray(cam, 64, 48, int(i), int(j), &o, &d);
          const glm::dvec3 oc = o - centre;
          const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
          double th = INFINITY;
          if (disc >= 0) th = -b - std::sqrt(disc) > 0 ? -b - std::sqrt(disc) : -b + std::sqrt(disc);
          const bool hit = th > 0 && std::isfinite(th);
          ClipRegion keep;
          if (hit) keep.planes.push_back({d, -glm::dot(d, o + th * d)});
          const double T = std::exp(-tau * test::box_chord(o, d, lo, hi, keep));
          const float* px = sink.image.at(i, j);
          for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(px[k] - (c[k] * (1 - T) + T * (hit ? sc[k] : bg[k]))));
          worst = std::max(worst, std::abs(px[3] - ((1 - T) + T * (hit ? 1.0 : bg[3]))));
        }
      EXPECT_LE(worst, 2e-5) << proj << (inside ? ", inside" : "");
      const nlohmann::json st = job->stats(*r, FrameReport{});
      EXPECT_GT(st["rays_stopped_by_geometry"].get<uint64_t>(), 5u) << proj;
      EXPECT_EQ(st["geometry"]["renderer"], "spheres");
      // The reference: Embree's sphere under its own volume walk.
      const ReferenceImage ref = reference_image(in, 0);
      double rworst = 0;
      for (size_t p = 0; p < size_t(64) * 48; ++p)
        for (int k = 0; k < 4; ++k)
          rworst = std::max(rworst, double(std::abs(ref.pixels[p * ref.names.size() + size_t(k)] -
                                                    sink.image.rgba[p * 4 + size_t(k)])));
      EXPECT_LE(rworst, 2e-5) << proj << (inside ? ", inside" : "");
      // Every ray that meets the sphere crosses the box first (it is inside).
      EXPECT_EQ(ref.stats["rays_stopped_by_geometry"], st["rays_stopped_by_geometry"]);
    }
}

TEST(MixedScene, SceneRules) {
  auto error_of = [](const std::string& json) {
    try {
      parse_scene(json, "s.json", "");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of(R"({"mesh": "m.off", "spheres": "s.sph", "render": {"mode": "weighted"}})"),
            "s.json: spheres inside a volume are opaque: translucent spheres (render.mode) would need the volume's "
            "segments sorted against every sphere layer, which zsweep does not do");
  EXPECT_EQ(error_of(R"({"spheres": "s.sph", "surfaces": ["c.obj"]})"),
            "s.json: a scene has one of 'mesh', 'spheres' or 'surfaces' (or a 'mesh' with either or both of the "
            "others)");
  EXPECT_EQ(error_of(R"({"mesh": "m.off", "spheres": "s.sph", "surfaces": ["c.obj"], "clip_geometry": true})"),
            "s.json: clip_geometry cuts surfaces; spheres are not cut (drop it, or the spheres)");
  const Scene both = parse_scene(R"({"mesh": "m.off", "spheres": "s.sph", "surfaces": [{"boundary": true}],
    "shading": {"model": "phong", "light_direction": [0, -1, 0], "ambient": 0.4}})", "s.json", "");
  EXPECT_TRUE(both.with_spheres && both.with_surfaces);
  EXPECT_EQ(both.spheres.shading.ambient, 0.4);  // shared
  EXPECT_EQ(both.surfaces.shading.ambient, 0.4);
  EXPECT_EQ(both.surfaces.surfaces[0].source, SurfaceSource::Boundary);
  const Scene s = parse_scene(R"({"mesh": "m.off", "surfaces": ["c.obj"], "lights": [{"type": "directional",
    "direction": [0, -1, 0]}], "render": {"scan": "bbox"}, "transfer_function": {"color": [[0, 1, 1, 1]],
    "opacity": [[0, 0.5]]}})", "s.json", "");
  EXPECT_EQ(s.kind, SceneKind::Volume);
  EXPECT_TRUE(s.with_surfaces);
  EXPECT_EQ(s.settings.scan, ScanStrategy::BBox);
  EXPECT_EQ(s.surfaces.lights.size(), 1u);
}

}  // namespace
}  // namespace zs
