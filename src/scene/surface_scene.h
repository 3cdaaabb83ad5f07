// The surface renderer's part of a scene (docs/shadows.md): its triangle
// meshes, ground plane, lights, shading and shadows. Image, camera and
// memory budget are the common ones (Scene::settings).
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>

#include "lighting/light.h"
#include "lighting/shadow_settings.h"
#include "render/surfaces/surface_settings.h"
#include "lighting/surface_shading.h"

namespace zs {

// Where a surface comes from: a triangle file (or data), or — inside a volume
// scene — the volume's mesh: its boundary, or isosurfaces of its scalar
// (geometry/triangles/io/mesh_surfaces.h).
enum class SurfaceSource { File, Boundary, Isosurface };

struct SurfaceEntry {
  SurfaceSource source = SurfaceSource::File;
  std::string path;  // resolved against the scene's directory (File)
  std::vector<double> iso_values;  // Isosurface
  glm::dvec3 color{0.8, 0.8, 0.8};
  // p' = translate + R·(scale·p), R = Rz·Ry·Rx of rotate_deg (x first).
  glm::dvec3 translate{0.0}, rotate_deg{0.0};
  double scale = 1;
};

struct SurfaceScene {
  std::vector<SurfaceEntry> surfaces;
  bool ground = false;        // a square under the surfaces (scene_input.h)
  bool ground_auto_height = false;  // bare mesh: at the mesh's lowest point
  double ground_height = 0;
  glm::dvec3 ground_color{0.9, 0.9, 0.9};
  bool has_lights = false;    // false: one directional light, direction (-1, -2, -1)
  std::vector<Light> lights;
  SurfaceShading shading;
  ShadowSettings shadows;
  bool shadows_enabled = true;
  bool cull_back = true, cull_view = true;
};

namespace scene_json {
struct Ctx;
}
struct Scene;

// Parses a scene's `surfaces`, `ground`, `lights`, `shading`, `shadows` and
// surface `render` keys into s->surfaces (throws as load_scene does);
// render_keys false: `render` is another renderer's (a volume's).
void parse_surface_blocks(const scene_json::Ctx& c, const nlohmann::json& j, Scene* s, bool render_keys = true);

// The settings a SurfaceRenderer takes, from a scene's common and surface
// parts (colours: the surfaces', then the ground's).
struct RenderSettings;
SurfaceRenderSettings surface_render_settings(const RenderSettings& common, const SurfaceScene& ss);

}  // namespace zs
