// `zsweep reference SCENE.json|MESH -o OUT.exr [--stats S.json]`: the
// independent ray caster every error figure is measured against.
// `zsweep reference FILE.sph|FILE.pdb -o OUT.exr`: the sphere renderers'
// Embree reference, with an automatic camera and the default shading (a
// scene format for spheres is still to come).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/scene_args.h"
#include "mesh/topology.h"
#include "reference/reference_renderer.h"
#include "reference/sphere_reference.h"
#include "spheres/sphere_colors.h"
#include "spheres/sphere_io.h"
#include "util/atomic_file.h"

namespace zs {

namespace {

// Looking down −z with y up at the bounding box of the drawable spheres,
// which fills the image with a 5 % margin; the eye (or the orthographic eye
// plane) well in front of the nearest sphere.
Camera sphere_auto_camera(const SphereSet& s, Projection p, uint32_t width, uint32_t height) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i < s.size(); ++i) {
    const double r = s.radii[i];
    const glm::dvec3& c = s.centres[i];
    if (!(r > 0) || !std::isfinite(r) || !std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) continue;
    lo = glm::min(lo, c - r), hi = glm::max(hi, c + r);
  }
  if (!(lo.x <= hi.x)) lo = glm::dvec3(-1), hi = glm::dvec3(1);
  const glm::dvec3 c = 0.5 * (lo + hi), e = hi - lo;
  const double aspect = double(width) / double(height), diag = std::max(glm::length(e), 1e-300);
  Camera cam;
  cam.projection = p;
  cam.target = c;
  cam.up = {0, 1, 0};
  cam.height = 1.05 * std::max(e.y, e.x / aspect);
  if (!(cam.height > 0)) cam.height = diag;
  cam.fov_y = 30.0;
  if (p == Projection::Orthographic) {
    cam.eye = {c.x, c.y, hi.z + 0.5 * diag};
  } else {
    // The bounding sphere fits the narrower field of view.
    const double half = std::atan(std::tan(cam.fov_y * M_PI / 360.0) * std::min(1.0, aspect));
    cam.eye = c + glm::dvec3(0, 0, 0.55 * diag / std::sin(half));
  }
  return cam;
}

// Colours as the sphere renderer's default mode picks them; a scalar goes
// through a blue–white–red ramp over its finite range (non-finite: grey).
std::vector<glm::vec4> default_sphere_colors(const SphereSet& s) {
  const SphereColorMode mode = default_color_mode(s);
  if (mode != SphereColorMode::Scalar) return sphere_colors(s, mode, TransferFunction());
  double lo = INFINITY, hi = -INFINITY;
  for (double v : s.scalars)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(lo < hi)) lo = (std::isfinite(lo) ? lo : 0) - 1, hi = lo + 2;
  const TransferFunction tf({{lo, 0.23, 0.30, 0.75}, {0.5 * lo + 0.5 * hi, 0.87, 0.87, 0.87}, {hi, 0.71, 0.02, 0.15}},
                            {{lo, 1.0}, {hi, 1.0}});
  std::vector<glm::vec4> col = sphere_colors(s, mode, tf);
  for (size_t i = 0; i < s.size(); ++i)
    if (!std::isfinite(s.scalars[i])) col[i] = element_color(0);
  return col;
}

void reference_spheres(const SceneArgs& a, const std::string& out) {
  Projection p = Projection::Orthographic;
  if (a.projection == "perspective") p = Projection::Perspective;
  else if (!a.projection.empty() && a.projection != "orthographic")
    throw std::runtime_error("--projection must be orthographic or perspective");
  const SphereSet set = read_sphere_file(a.input);
  AtomicFile(out).check_writable();
  const uint32_t w = a.width ? a.width : 1024, h = a.height ? a.height : 1024;
  const View view(sphere_auto_camera(set, p, w, h), w, h);
  const double background[4] = {0, 0, 0, 0};
  const SphereReferenceImage img =
      render_sphere_reference(set, default_sphere_colors(set), Shading{}, view, background, a.threads);
  write_image(out, img.rgba);
  std::printf("wrote %s: %ux%u, %zu spheres (%zu left out), %llu pixels hit, BVH %.1f ms, trace %.1f ms\n",
              out.c_str(), w, h, set.size(), img.invalid, (unsigned long long)img.hits, img.ms_build, img.ms_trace);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>(), stats = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "reference", "Ground-truth image: an independent ray caster (tet walk, exact integration, no early termination; "
      "sphere files: Embree with exact hits, automatic camera)");
  a->add_options(*cmd, false);
  cmd->add_option("-o,--output", *out, "Output image (.exr or .tif keep the float values)")->required();
  cmd->add_option("--stats", *stats, "Write ray-casting statistics as JSON");
  cmd->callback([a, out, stats] {
    if (is_sphere_file(a->input)) {
      if (!stats->empty()) throw std::runtime_error("--stats is for tet meshes, not sphere files");
      reference_spheres(*a, *out);
      return;
    }
    SceneInput in = a->load();
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
      AtomicFile f(*stats);
      {
        std::ofstream o(f.temp_path());
        o << j.dump(2) << "\n";
        if (!o) throw std::runtime_error(*stats + ": cannot write stats");
      }
      f.commit();
    }
    std::printf("wrote %s: %ux%u, %llu rays hit, %llu segments, %llu lost walks, %.1f ms\n", out->c_str(), img.width,
                img.height, (unsigned long long)s.rays_hit, (unsigned long long)s.segments,
                (unsigned long long)s.lost_walks, s.ms_total);
  });
}

}  // namespace zs
