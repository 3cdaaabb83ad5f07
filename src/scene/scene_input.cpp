#include "scene/scene_input.h"

#include <chrono>
#include <cmath>

#include <glm/common.hpp>
#include <stdexcept>

#include "geometry/tets/default_mesh.h"
#include "scene/surface_input.h"
#include "geometry/spheres/sphere_io.h"
#include "geometry/triangles/io/surface_reader.h"

namespace zs {

Scene default_scene() {
  Scene s;
  RenderSettings& rs = s.settings;
  rs.width = rs.height = 512;
  rs.camera.projection = Projection::Perspective;
  rs.camera.eye = {2.6, 1.6, 3.4};
  rs.camera.target = {0, 0, 0};
  rs.camera.up = {0, 1, 0};
  rs.camera.fov_y = 35;
  rs.background[0] = rs.background[1] = rs.background[2] = 0.0;
  rs.background[3] = 1.0;
  rs.tf = TransferFunction({{0.0, 0.1, 0.2, 0.6}, {0.3, 0.1, 0.7, 0.8}, {0.6, 0.95, 0.85, 0.3}, {1.0, 0.9, 0.2, 0.1}},
                           {{0.0, 0.0}, {0.15, 0.0}, {0.35, 0.08}, {0.6, 0.25}, {1.0, 0.8}}, 0.1);
  s.has_camera = s.has_transfer_function = true;
  return s;
}

namespace {

// The scene's mesh, sphere set or surfaces, from `data` or their files.
void load_spheres(SceneInput& in, const SceneData* data, const MoleculeOverrides& molecule) {
  const std::string& path = in.scene.spheres.path;
  molecule.apply(in.scene.spheres.molecule);
  in.spheres = data && data->spheres.count(path) ? data->spheres.at(path)
                                                 : read_sphere_file(path, in.scene.spheres.molecule);
  if (in.scene.spheres.radius_scale != 1.0)
    for (double& r : in.spheres.radii) r *= in.scene.spheres.radius_scale;
}

void load_scene_data(SceneInput& in, const SceneData* data, const MoleculeOverrides& molecule) {
  const auto t0 = std::chrono::steady_clock::now();
  if (in.scene.kind == SceneKind::Volume) {  // first: a volume's surfaces may be made of its mesh
    const std::string& path = in.scene.mesh_path;
    if (data && data->meshes.count(path)) {
      in.mesh = data->meshes.at(path);
    } else {
      in.mesh = path.empty() ? default_mesh() : read_mesh(path, in.scene.mesh_options);
    }
    if (in.mesh.num_tets() == 0) throw std::runtime_error(path + ": mesh has no tets");
  }
  if (in.scene.kind == SceneKind::Spheres || in.scene.with_spheres) load_spheres(in, data, molecule);
  if (in.scene.kind == SceneKind::Surfaces || in.scene.with_surfaces) load_surfaces(in, data ? &data->surfaces : nullptr);
  in.ms_load = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SceneInput load_scene_input(const std::string& input, const ReadOptions& mesh_options,
                            const MoleculeOverrides& molecule) {
  SceneInput in;
  if (input.empty()) {
    in.scene = default_scene();
  } else if (input.size() > 5 && input.compare(input.size() - 5, 5, ".json") == 0) {
    in.scene = load_scene(input);
  } else if (is_sphere_file(input)) {
    in.scene.kind = SceneKind::Spheres;
    in.scene.spheres.path = input;
  } else if (is_surface_file(input)) {
    in.scene.kind = SceneKind::Surfaces;
    SurfaceEntry e;
    e.path = input;
    in.scene.surfaces.surfaces.push_back(e);
    in.scene.surfaces.ground = in.scene.surfaces.ground_auto_height = true;
  } else {
    in.scene.mesh_path = input;
    in.scene.mesh_options = mesh_options;
  }
  load_scene_data(in, nullptr, molecule);
  return in;
}

SceneInput load_scene_input_text(const std::string& json_text, const std::string& name, const std::string& base_dir,
                                 const SceneData& data, const MoleculeOverrides& molecule) {
  SceneInput in;
  in.scene = parse_scene(json_text, name, base_dir);
  load_scene_data(in, &data, molecule);
  return in;
}

void finish_scene(SceneInput& in, Projection auto_projection) {
  RenderSettings& rs = in.scene.settings;
  if (in.scene.kind == SceneKind::Surfaces) {
    if (in.scene.has_camera) return;
    // Framed on the surfaces (not the ground: it is only there to receive).
    const TriangleMesh& only = in.surface;
    const uint32_t ground = uint32_t(in.scene.surfaces.surfaces.size());
    Bounds b;
    for (size_t t = 0; t < only.tris.size(); ++t)
      if (only.surface[t] != ground)
        for (uint32_t v : only.tris[t]) {
          const glm::dvec3& p = only.points[v];
          b.lo = b.empty ? p : glm::min(b.lo, p);
          b.hi = b.empty ? p : glm::max(b.hi, p);
          b.empty = false;
        }
    try {
      rs.camera = frame_surfaces(b, auto_projection, rs.width, rs.height);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(in.scene.surfaces.surfaces[0].path + ": " + e.what());
    }
    return;
  }
  if (in.scene.kind == SceneKind::Spheres) {
    // Framed on the box of the drawable spheres, radii included.
    Bounds b;
    for (size_t i = 0; i < in.spheres.size(); ++i) {
      const glm::dvec3& c = in.spheres.centres[i];
      const double r = in.spheres.radii[i];
      if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(r) && r > 0)) continue;
      b.lo = b.empty ? c - r : glm::min(b.lo, c - r);
      b.hi = b.empty ? c + r : glm::max(b.hi, c + r);
      b.empty = false;
    }
    if (!in.scene.has_camera) {
      try {
        rs.camera = frame_bounds(b, auto_projection, rs.width, rs.height);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(in.scene.spheres.path + ": " + e.what());
      }
    }
    if (!in.scene.has_transfer_function)
      rs.tf = default_transfer_function(in.spheres.scalars, 1.0);
    return;
  }
  if (!in.scene.has_camera) {
    try {
      rs.camera = auto_camera(in.mesh, auto_projection, rs.width, rs.height);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error((in.scene.mesh_path.empty() ? std::string("default mesh") : in.scene.mesh_path) + ": " +
                               e.what());
    }
  }
  if (!in.scene.has_transfer_function) rs.tf = default_transfer_function(in.mesh);
}

}  // namespace zs
