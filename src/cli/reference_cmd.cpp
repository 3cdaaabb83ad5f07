// `zsweep reference SCENE.json|MESH -o OUT.exr [--stats S.json]`: the
// independent ray caster every error figure is measured against.
// Sphere scenes and files (.pdb/.sph/.sphb): the sphere renderers' Embree
// reference, on the scene's camera, colours and shading (RGBA and Z).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/json_out.h"
#include "cli/render_surfaces.h"
#include "cli/scene_args.h"
#include "mesh/topology.h"
#include "reference/reference_renderer.h"
#include "reference/sphere_reference.h"
#include "shadows/ao_directions.h"
#include "spheres/sphere_colors.h"
#include "image/tile_writer.h"
#include "util/atomic_file.h"

namespace zs {

namespace {

// Writes RGBA and, for EXR/TIFF, the Z channel, through the tile writer
// (as `render` writes them).
// With `ao`, a sixth channel AO (as `render` writes it).
void write_rgba_z(const std::string& path, const Image& img, const std::vector<float>& z,
                  const std::vector<float>* ao = nullptr) {
  const uint32_t C = ao ? 6 : 5;
  const TileGrid grid{img.width, img.height, 64, C};
  ImageTileWriter w(path, grid, "", ao ? std::vector<std::string>{"R", "G", "B", "A", "Z", "AO"} : std::vector<std::string>{});
  std::vector<float> buf;
  for (uint32_t t = 0; t < grid.count(); ++t) {
    const TileRect r = grid.rect(t);
    buf.resize(size_t(r.width()) * r.height() * C);
    for (uint32_t y = r.y0; y < r.y1; ++y)
      for (uint32_t x = r.x0; x < r.x1; ++x) {
        float* o = &buf[(size_t(y - r.y0) * r.width() + (x - r.x0)) * C];
        std::copy(img.at(x, y), img.at(x, y) + 4, o);
        o[4] = z[size_t(y) * img.width + x];
        if (ao) o[5] = (*ao)[size_t(y) * img.width + x];
      }
    w.tile(r, buf.data());
  }
  w.commit();
}

// The sphere scene as `render` sees it (camera, colours, shading,
// background), traced by Embree with exact hits.
void reference_spheres(SceneInput& in, const std::string& out, const std::string& stats, int threads,
                       uint32_t ao_samples) {
  AtomicFile(out).check_writable();
  if (!stats.empty()) AtomicFile(stats).check_writable();
  const RenderSettings& rs = in.scene.settings;
  const SphereScene& sp = in.scene.spheres;
  const SphereColorMode mode = sp.has_color_mode ? sp.color : default_color_mode(in.spheres);
  std::vector<glm::vec4> colors;
  try {
    colors = sphere_colors(in.spheres, mode, rs.tf);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(sp.path + ": " + e.what());
  }
  const View view(rs.camera, rs.width, rs.height);
  // Translucent modes: every crossing composited in order, exactly (no
  // tolerance, no layer cap): what each mode approximates.
  // Ambient occlusion: exact rays over the scene's directions, or Monte
  // Carlo with --ao-samples rays per pixel.
  std::vector<float> ao;
  SphereAoSpec spec;
  spec.dirs = sp.ao.directions ? ao_directions(sp.ao.directions) : std::vector<glm::dvec3>{};
  spec.samples = ao_samples;
  spec.alpha_occluders = sp.ao.alpha_occluders;
  const SphereReferenceImage img =
      sp.mode == SphereMode::Opaque
          ? (sp.ao.directions
                 ? render_sphere_reference_ao(in.spheres, colors, sp.shading, view, rs.background, threads, spec, &ao)
                 : render_sphere_reference(in.spheres, colors, sp.shading, view, rs.background, threads))
          : render_sphere_reference_translucent(in.spheres, colors, sp.shading, view, rs.background, threads,
                                                sp.front_surfaces_only, sp.ao.directions ? &spec : nullptr, &ao);
  write_rgba_z(out, img.rgba, img.z, sp.ao.directions ? &ao : nullptr);
  if (!stats.empty()) {
    nlohmann::json j = {{"time_ms", {{"build", img.ms_build}, {"trace", img.ms_trace}, {"total", img.ms_build + img.ms_trace}}},
                        {"spheres", in.spheres.size()},
                        {"invalid", img.invalid},
                        {"pixels_hit", img.hits},
                        {"image", {{"width", rs.width}, {"height", rs.height}}}};
    write_json_file(stats, j);
  }
  std::printf("wrote %s: %ux%u, %zu spheres (%zu left out), %llu pixels hit, BVH %.1f ms, trace %.1f ms\n",
              out.c_str(), rs.width, rs.height, in.spheres.size(), img.invalid, (unsigned long long)img.hits,
              img.ms_build, img.ms_trace);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>(), stats = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "reference", "Ground-truth image: an independent ray caster (tet walk, exact integration, no early termination; "
      "sphere scenes: Embree with exact hits; surface scenes: Embree shadow rays)");
  a->add_options(*cmd, false);
  cmd->add_option("-o,--output", *out, "Output image (.exr or .tif keep the float values)")->required();
  cmd->add_option("--stats", *stats, "Write ray-casting statistics as JSON");
  auto ao_samples = std::make_shared<uint32_t>(0);
  cmd->add_option("--ao-samples", *ao_samples,
                  "Sphere scenes with ao: 0 (default) traces the scene's directions exactly; N > 0 a cosine-weighted "
                  "Monte Carlo AO with N rays per pixel")
      ->check(CLI::Range(0u, 1u << 20));
  cmd->callback([a, out, stats, ao_samples] {
    SceneInput in = a->load();
    if (*ao_samples && !(in.scene.kind == SceneKind::Spheres && in.scene.spheres.ao.directions))
      throw std::runtime_error(a->input + ": --ao-samples needs a sphere scene with an 'ao' block");
    if (in.scene.kind == SceneKind::Spheres) {
      reference_spheres(in, *out, *stats, in.scene.settings.threads, *ao_samples);
      return;
    }
    if (in.scene.kind == SceneKind::Surfaces) {
      // The surface renderer's ground truth is its exact mode: one Embree
      // shadow ray per visible pixel and light (docs/shadows.md).
      in.scene.surfaces.shadows.mode = ShadowMode::Exact;
      if (!stats->empty()) AtomicFile(*stats).check_writable();
      run_surfaces(in, *out, *stats, 1, "");
      return;
    }
    AtomicFile(*out).check_writable();  // before minutes of ray casting
    if (!stats->empty()) AtomicFile(*stats).check_writable();
    const Topology topo = build_topology(in.mesh);
    ReferenceStats s;
    const Image img = render_reference(in.mesh, topo, in.scene.settings, &s);
    write_image(*out, img);
    if (!stats->empty()) {
      nlohmann::json j = {{"time_ms", s.ms_total},       {"rays_hit", s.rays_hit},
                          {"segments", s.segments},      {"tet_steps", s.tet_steps},
                          {"entries", s.entries},        {"lost_walks", s.lost_walks}, {"flat_tets", s.flat_tets},
                          {"boundary_faces", s.boundary_faces}, {"unbinned_faces", s.unbinned_faces},
                          {"image", {{"width", img.width}, {"height", img.height}}}};
      write_json_file(*stats, j);
    }
    std::printf("wrote %s: %ux%u, %llu rays hit, %llu segments, %llu lost walks, %.1f ms\n", out->c_str(), img.width,
                img.height, (unsigned long long)s.rays_hit, (unsigned long long)s.segments,
                (unsigned long long)s.lost_walks, s.ms_total);
  });
}

}  // namespace zs
