// Scene files (JSON). Unknown keys are errors; paths are relative to the
// scene file. See docs/scene.md for the format.
#pragma once

#include <string>

#include "geometry/tets/io/mesh_io.h"
#include "scene/scene_defaults.h"
#include "scene/surface_scene.h"
#include "geometry/spheres/molecule_reader.h"
#include "geometry/spheres/sphere_colors.h"
#include "render/spheres/sphere_settings.h"
#include "render/volume/render_settings.h"

namespace zs {

// Which renderer a scene is for: its top-level `mesh`, `spheres` or
// `surfaces` key (a `mesh` with `spheres` or `surfaces` is a volume scene
// with geometry in it).
enum class SceneKind { Volume, Spheres, Surfaces };

// The sphere renderer's part of a scene (docs/spheres.md): the set, how it is
// coloured, lit and rendered. Image, camera, transfer function and memory
// budget are the volume scene's (Scene::settings).
struct SphereScene {
  std::string path;  // resolved against the scene's directory
  double radius_scale = 1.0;
  MoleculeOptions molecule;  // spheres.model, .waters, .hydrogens (molecule files only)
  bool has_color_mode = false;  // false: default_color_mode of the set
  SphereColorMode color = SphereColorMode::Element;
  Shading shading;
  SphereAo ao;                       // the `ao` block; directions 0: off
  SphereMode mode = SphereMode::Opaque;
  bool front_surfaces_only = false;  // render.surfaces: "front"
  double tolerance = 8;              // render.tolerance
  uint32_t max_layers = 32;          // render.max_layers
  uint32_t grid = 0;  // render.grid; 0: "auto"
  bool culling = true;
};

// The settings a SphereRenderer takes, from a scene's common and sphere parts.
SphereRenderSettings sphere_render_settings(const RenderSettings& common, const SphereScene& sp);

struct Scene {
  SceneKind kind = SceneKind::Volume;
  std::string mesh_path;  // resolved against the scene's directory
  ReadOptions mesh_options;
  SphereScene spheres;    // kind == Spheres
  SurfaceScene surfaces;  // kind == Surfaces
  RenderSettings settings;
  // A volume scene with opaque geometry inside it (docs/scene.md, "Volumes
  // with geometry"): the spheres or surfaces parts above, drawn first.
  bool with_spheres = false, with_surfaces = false;
  bool clip_geometry = false;  // the clip planes cut the surfaces too (not only the volume)
  bool has_camera = false;             // false: frame the mesh automatically
  bool has_transfer_function = false;  // false: default ramp over the scalar range
  bool mixed() const { return with_spheres || with_surfaces; }
};

// Throws std::runtime_error("FILE: what") for unreadable files, JSON syntax
// errors (with line) and invalid or unknown keys.
Scene load_scene(const std::string& path);
Scene parse_scene(const std::string& json_text, const std::string& name, const std::string& base_dir);
// A scene's "camera" object as JSON text, over `camera`: the keys it names
// replace camera's, then it is checked as a scene's is; errors name `name`.
void parse_camera_json(const std::string& json_text, const std::string& name, Camera* camera);


}  // namespace zs
