// Scene files (JSON). Unknown keys are errors; paths are relative to the
// scene file. See docs/scene.md for the format.
#pragma once

#include <string>

#include "mesh/io/mesh_io.h"
#include "scene/scene_defaults.h"
#include "volume/render_settings.h"

namespace zs {

struct Scene {
  std::string mesh_path;  // resolved against the scene's directory
  ReadOptions mesh_options;
  RenderSettings settings;
  bool has_camera = false;             // false: frame the mesh automatically
  bool has_transfer_function = false;  // false: default ramp over the scalar range
};

// Throws std::runtime_error("FILE: what") for unreadable files, JSON syntax
// errors (with line) and invalid or unknown keys.
Scene load_scene(const std::string& path);
Scene parse_scene(const std::string& json_text, const std::string& name, const std::string& base_dir);


}  // namespace zs
