#include "app/reference_scene.h"

#include <cstdarg>
#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "app/scene_job.h"
#include "app/scene_jobs.h"
#include "raster/image_sink.h"
#include "geometry/tets/topology.h"
#include "geometry/tets/validate.h"
#include "render/reference/reference_renderer.h"
#include "render/reference/sphere_reference.h"
#include "lighting/ao_directions.h"
#include "geometry/spheres/sphere_colors.h"

namespace zs {

namespace {

std::string line(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string line(const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

// The sphere scene as `render` sees it (camera, colours, shading,
// background), traced by Embree with exact hits.
ReferenceImage reference_spheres(SceneInput& in, uint32_t ao_samples) {
  const RenderSettings& rs = in.scene.settings;
  const SphereScene& sp = in.scene.spheres;
  const int threads = rs.threads;
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
  // Carlo with `ao_samples` rays per pixel.
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
  ReferenceImage out;
  out.width = rs.width;
  out.height = rs.height;
  out.names = {"R", "G", "B", "A", "Z"};
  if (sp.ao.directions) out.names.push_back("AO");
  const size_t C = out.names.size(), n = size_t(rs.width) * rs.height;
  out.pixels.resize(n * C);
  for (size_t p = 0; p < n; ++p) {
    float* o = &out.pixels[p * C];
    for (int k = 0; k < 4; ++k) o[k] = img.rgba.rgba[p * 4 + k];
    o[4] = img.z[p];
    if (C == 6) o[5] = ao[p];
  }
  out.stats = {{"time_ms", {{"build", img.ms_build}, {"trace", img.ms_trace}, {"total", img.ms_build + img.ms_trace}}},
               {"spheres", in.spheres.size()},
               {"invalid", img.invalid},
               {"pixels_hit", img.hits},
               {"image", {{"width", rs.width}, {"height", rs.height}}}};
  out.summary = line("%ux%u, %zu spheres (%zu left out), %llu pixels hit, BVH %.1f ms, trace %.1f ms", rs.width,
                     rs.height, in.spheres.size(), img.invalid + in.spheres.invalid, (unsigned long long)img.hits, img.ms_build,
                     img.ms_trace);
  return out;
}

// A mixed scene's geometry as the volume's reference sees it: spheres traced
// by Embree (reference_spheres), surfaces drawn by their renderer with exact
// shadow rays (their reference, as for surface scenes). RGBA and view depth
// per pixel, its stats.
struct UnderImage {
  Image rgba;
  std::vector<float> z;
  nlohmann::json stats;
};
UnderImage reference_spheres_under(SceneInput& in) {
  UnderImage u;
  const ReferenceImage r = reference_spheres(in, 0);
  const size_t C = r.names.size(), n = size_t(r.width) * r.height;
  u.rgba = Image(r.width, r.height);
  u.z.resize(n);
  for (size_t p = 0; p < n; ++p) {
    for (int k = 0; k < 4; ++k) u.rgba.rgba[p * 4 + size_t(k)] = r.pixels[p * C + size_t(k)];
    u.z[p] = r.pixels[p * C + 4];
  }
  u.stats = r.stats;
  u.stats["renderer"] = "spheres (Embree)";
  return u;
}

UnderImage reference_surfaces_under(SceneInput& in) {
  UnderImage u;
  const RenderSettings& rs = in.scene.settings;
  in.scene.surfaces.shadows.mode = ShadowMode::Exact;  // shadow rays, not maps: the surfaces' reference
  std::unique_ptr<SceneJob> job = make_surface_job(in);
  ImageSink sink(job->grid());
  auto r = job->renderer(uint64_t(rs.width) * rs.height * 20, false);
  r->render_tiles(sink, nullptr);
  u.rgba = std::move(sink.image);
  u.z = std::move(sink.z);
  u.stats = job->stats(*r, FrameReport{});
  u.stats["renderer"] = "surfaces (the renderer, exact shadows)";
  return u;
}

// Spheres and/or surfaces; with both, each pixel the nearer (as the render's
// mixed job keeps it).
UnderImage reference_geometry(SceneInput& in) {
  if (!in.scene.with_surfaces) return reference_spheres_under(in);
  if (!in.scene.with_spheres) return reference_surfaces_under(in);
  UnderImage a = reference_spheres_under(in), b = reference_surfaces_under(in);
  for (size_t p = 0; p < a.z.size(); ++p)
    if (b.z[p] < a.z[p]) {
      a.z[p] = b.z[p];
      std::copy_n(&b.rgba.rgba[p * 4], 4, &a.rgba.rgba[p * 4]);
    }
  a.stats = {{"renderer", "spheres and surfaces"}, {"spheres", a.stats}, {"surfaces", b.stats}};
  return a;
}

ReferenceImage reference_volume(SceneInput& in) {
  const Topology topo = build_topology(in.mesh);
  ReferenceStats s;
  UnderImage geometry;
  ReferenceUnder under;
  if (in.scene.mixed()) {
    geometry = reference_geometry(in);
    under = {&geometry.rgba, geometry.z.data()};
  }
  Image img = render_reference(in.mesh, topo, in.scene.settings, in.scene.settings.tf, &s,
                               in.scene.mixed() ? &under : nullptr);
  ReferenceImage out;
  out.width = img.width;
  out.height = img.height;
  out.names = {"R", "G", "B", "A"};
  out.pixels = std::move(img.rgba);
  out.stats = {{"time_ms", s.ms_total},       {"rays_hit", s.rays_hit},
               {"segments", s.segments},      {"tet_steps", s.tet_steps},
               {"entries", s.entries},        {"lost_walks", s.lost_walks}, {"segments_clipped", s.segments_clipped}, {"flat_tets", s.flat_tets},
               {"boundary_faces", s.boundary_faces}, {"unbinned_faces", s.unbinned_faces},
               {"image", {{"width", out.width}, {"height", out.height}}}};
  if (in.scene.mixed()) {
    out.stats["rays_stopped_by_geometry"] = s.rays_stopped;
    out.stats["geometry"] = geometry.stats;
  }
  out.summary = line("%ux%u, %llu rays hit, %llu segments, %llu lost walks, %.1f ms", out.width, out.height,
                     (unsigned long long)s.rays_hit, (unsigned long long)s.segments,
                     (unsigned long long)s.lost_walks, s.ms_total) +
                left_out_note({{count_nonfinite_tets(in.mesh), "tet with a non-finite coordinate or scalar",
                                "tets with a non-finite coordinate or scalar"}});
  return out;
}

}  // namespace

ReferenceImage reference_image(SceneInput& in, uint32_t ao_samples) {
  if (ao_samples && !(in.scene.kind == SceneKind::Spheres && in.scene.spheres.ao.directions))
    throw std::runtime_error("AO samples need a sphere scene with an 'ao' block");
  if (in.scene.kind == SceneKind::Spheres) return reference_spheres(in, ao_samples);
  if (in.scene.kind == SceneKind::Surfaces)
    throw std::runtime_error("surface scenes: the reference is the renderer's exact mode");
  return reference_volume(in);
}

}  // namespace zs
