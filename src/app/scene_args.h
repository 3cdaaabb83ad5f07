// Options shared by `render`, `reference` and the Python module's render: the input (scene,
// mesh or nothing), mesh options, size and camera overrides, threads, and —
// for the engine only — the speed/accuracy knobs.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene_input.h"

namespace CLI {
class App;
}

namespace zs {

struct SceneArgs {
  std::string input;
  ReadOptions opt;
  int threads = 0;  // 0 = every core
  uint32_t width = 0, height = 0;
  std::string projection;
  // Engine knobs.
  std::string scan, variant, integrator, precision;
  double memory_budget_mb = 0;
  double early_termination = -1;
  int64_t max_list_length = -1;
  uint32_t tile_size = 0;  // 0 = the engine's default

  void add_options(CLI::App& cmd, bool engine_knobs);
  // Loads the input and applies every override; camera and TF are complete.
  SceneInput load() const;
  // The same overrides on a scene loaded otherwise (the Python module's).
  void apply(SceneInput& in) const;

 private:
  // Throws on a bad knob; returns them parsed.
  RenderSettings check() const;
};

}  // namespace zs
