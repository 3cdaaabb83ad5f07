// Options shared by `render`, `reference` and the Python module's render: the input (scene,
// mesh or nothing), mesh options, size and camera overrides, threads, and —
// for the engine only — the speed/accuracy knobs. Every check of them (ranges,
// and which input kinds each applies to: app/option_checks.h) is made here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/option_checks.h"
#include "scene/scene_input.h"

namespace CLI {
class App;
}

namespace zs {

// A numeric option and its allowed values: the command line's checks and the
// Python module's keywords (option_name(option, true)) read the same table.
struct NumberOption {
  const char* option;
  NumberRange range;
};
const std::vector<NumberOption>& scene_number_options();
const NumberRange& scene_number_range(const std::string& option);

struct SceneArgs {
  std::string input;
  ReadOptions opt;
  std::string association;  // --association (mesh file input), parsed into opt.association by load()
  int threads = 0;  // 0 = every core
  uint32_t width = 0, height = 0;
  std::string projection;
  // Engine knobs.
  std::string scan, variant, integrator, precision;
  double memory_budget_mb = 0;
  double early_termination = -1;
  int64_t max_list_length = -1;
  uint32_t tile_size = 0;  // 0 = the engine's default
  MoleculeOverrides molecule;  // --model, --no-waters, --no-hydrogens (molecule files)
  // Options of the caller's own that apply to some input kinds only
  // ("--no-culling", "--ao-samples"), checked with these.
  std::vector<std::string> also_given;
  bool python = false;  // name options in messages as the module's keywords

  void add_options(CLI::App& cmd, bool engine_knobs);
  // Loads the input and applies every override; camera and TF are complete.
  SceneInput load() const;
  // The mesh options with --association parsed (check() refuses a bad one).
  ReadOptions read_options() const;
  // The checks that need no file read: the knobs' names, and for a bare
  // file, the options that do not apply to its kind (by its name), so a
  // large input is not read only to be refused. apply() checks again.
  void check_before_load() const;
  // The same overrides on a scene loaded otherwise (the Python module's);
  // `name` names the input in messages (default: `input`).
  void apply(SceneInput& in, const std::string& name = "") const;

 private:
  // Throws on a bad knob; returns them parsed.
  RenderSettings check() const;
  // The options set, by their command-line names.
  std::vector<std::string> given() const;
};

}  // namespace zs
